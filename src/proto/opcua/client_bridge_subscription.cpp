// The client bridge's subscription to the PLC's outputs (client_bridge.hpp; OPC 10000-4 §5.12
// CreateMonitoredItems, §5.13 CreateSubscription and Publish): a monitored item per output, one
// Publish always posted, so that a poll only takes what has come and never waits for the
// server's publishing cycle.
#include <algorithm>

#include "core/clock.hpp"
#include "proto/opcua/client_bridge.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kCreateMonitoredItemsRequestId = 751, kCreateMonitoredItemsResponseId = 754,
                   kCreateSubscriptionRequestId = 787, kCreateSubscriptionResponseId = 790, kPublishRequestId = 826,
                   kPublishResponseId = 829, kDeleteSubscriptionsRequestId = 847, kDeleteSubscriptionsResponseId = 850;
constexpr uint32_t kDataChangeNotificationId = 811;  // its binary encoding
constexpr uint32_t kMonitoringModeReporting = 2;

}  // namespace

std::expected<void, std::string> ClientBridge::subscribe() {
  subscription_ = SubscriptionState{};
  if (!config_.subscribe || reads_.empty()) return {};
  const double intervalMs = std::max(1.0, static_cast<double>(config_.pollNs) / 1e6);
  // Keep-alives every half timeout: a server that has gone silent is noticed about as soon as
  // a Read would have noticed it.
  const uint32_t keepAlive = std::max(1u, static_cast<uint32_t>(static_cast<double>(config_.client.timeoutNs) / 2e6 / intervalMs));
  Writer& w = client_.beginRequest(kCreateSubscriptionRequestId);
  encode(w, intervalMs);  // RequestedPublishingInterval
  w.u32(3 * keepAlive);   // RequestedLifetimeCount: at least three keep-alives (§5.13.2)
  w.u32(keepAlive);       // RequestedMaxKeepAliveCount
  w.u32(0);               // MaxNotificationsPerPublish: no limit
  encode(w, true);        // PublishingEnabled
  w.u8(0);                // Priority
  auto reply = client_.call(kCreateSubscriptionResponseId);
  if (!reply) {
    if (reply.error().linkLost) return std::unexpected("lost the link creating a subscription: " + reply.error().text);
    pollInstead("refused a subscription (" + reply.error().text + ")");
    return {};
  }
  uint32_t id = 0, lifetime = 0, revisedKeepAlive = 0;
  double revisedMs = 0;
  if (!reply->u32(id) || !decode(*reply, revisedMs) || !reply->u32(lifetime) || !reply->u32(revisedKeepAlive) || !(revisedMs > 0))
    return std::unexpected(std::string("sent a malformed CreateSubscription response"));

  Writer& items = client_.beginRequest(kCreateMonitoredItemsRequestId);
  items.u32(id);
  items.u32(kTimestampsNeither);
  items.i32(static_cast<int32_t>(reads_.size()));
  for (size_t i : reads_) {
    encodeReadValueId(items, nodeIds_[i], kValueAttr);
    items.u32(kMonitoringModeReporting);
    items.u32(static_cast<uint32_t>(i));  // ClientHandle: the signal
    encode(items, revisedMs);             // SamplingInterval
    encode(items, ExtensionObject{});     // Filter: none (any change)
    items.u32(1);                         // QueueSize: the latest value is what counts
    encode(items, true);                  // DiscardOldest
  }
  auto created = client_.call(kCreateMonitoredItemsResponseId);
  if (!created) {
    if (created.error().linkLost) return std::unexpected("lost the link creating monitored items: " + created.error().text);
    pollInstead("refused the monitored items (" + created.error().text + ")");
    return {};
  }
  uint32_t count = 0;
  if (!created->arrayLength(count, 4) || count != reads_.size())
    return std::unexpected("answered CreateMonitoredItems with " + std::to_string(count) + " results for " + std::to_string(reads_.size()));
  for (size_t i : reads_) {
    uint32_t status = 0, itemId = 0, queue = 0;
    double sampling = 0;
    ExtensionObject filter;
    if (!created->u32(status) || !created->u32(itemId) || !decode(*created, sampling) || !created->u32(queue) || !decode(*created, filter))
      return std::unexpected(std::string("sent a malformed CreateMonitoredItems response"));
    if (isBad(status)) {
      pollInstead("refused monitoring '" + config_.signals[i].name + "' (" + statusName(status) + ")");
      Writer& del = client_.beginRequest(kDeleteSubscriptionsRequestId);
      del.i32(1);
      del.u32(id);
      if (auto deleted = client_.call(kDeleteSubscriptionsResponseId); !deleted && deleted.error().linkLost)
        return std::unexpected("lost the link deleting the subscription: " + deleted.error().text);
      return {};
    }
  }
  subscription_.id = id;
  subscription_.intervalMs = revisedMs;
  subscription_.silenceNs = static_cast<int64_t>((revisedKeepAlive + 1) * revisedMs * 1e6) + config_.client.timeoutNs;
  return {};
}

void ClientBridge::pollInstead(const std::string& why) {
  subscription_ = SubscriptionState{};
  if (config_.report) config_.report("opcua: " + peerText() + " " + why + ": its outputs are read every poll instead");
}

bool ClientBridge::postPublish() {
  Writer& w = client_.beginRequest(kPublishRequestId);
  w.i32(subscription_.ack ? 1 : 0);  // SubscriptionAcknowledgements
  if (subscription_.ack) {
    w.u32(subscription_.id);
    w.u32(subscription_.ackSequence);
  }
  subscription_.ack = false;
  if (auto posted = client_.post(); !posted) {
    lose("publishing: " + posted.error().text);
    return false;
  }
  subscription_.answerByNs = monotonicNowNs() + subscription_.silenceNs;
  return true;
}

bool ClientBridge::takePublished(TagBus& bus) {
  if (!client_.posted() && !postPublish()) return !link_.failed();
  auto reply = client_.collect(kPublishResponseId);
  if (!reply) {
    if (reply.error().linkLost) lose("publishing: " + reply.error().text);
    // BadTimeout: a Publish the server held past its TimeoutHint, posted again.
    else if (reply.error().status != static_cast<uint32_t>(StatusCodeValue::BadTimeout)) link_.refused("refused a Publish: " + reply.error().text);
    return !link_.failed();
  }
  if (!*reply) {
    if (monotonicNowNs() > subscription_.answerByNs)
      lose("no Publish answered within " + std::to_string(subscription_.silenceNs / 1'000'000) + " ms");
    return !link_.failed();
  }
  if (!takeNotifications(bus, **reply)) return !link_.failed();
  return postPublish() || !link_.failed();
}

// A PublishResponse's fields: SubscriptionId, AvailableSequenceNumbers, MoreNotifications, the
// NotificationMessage (SequenceNumber, PublishTime, NotificationData: ExtensionObjects, of which
// DataChangeNotifications carry MonitoredItemNotifications: ClientHandle, DataValue), Results.
bool ClientBridge::takeNotifications(TagBus& bus, Reader& r) {
  auto broken = [this](const std::string& what) {
    lose(what);
    return false;
  };
  uint32_t subscriptionId = 0, available = 0, sequence = 0, notifications = 0, skipped = 0;
  bool more = false;
  DateTime published;
  if (!r.u32(subscriptionId) || !r.arrayLength(available, 4)) return broken("a malformed Publish response");
  for (uint32_t n = 0; n < available; ++n)
    if (!r.u32(skipped)) return broken("a malformed Publish response");
  if (!decode(r, more) || !r.u32(sequence) || !decode(r, published) || !r.arrayLength(notifications, 3))
    return broken("a malformed Publish response");
  for (uint32_t n = 0; n < notifications; ++n) {
    NodeId type;
    uint8_t encoding = 0;
    int32_t length = 0;
    std::span<const uint8_t> body;
    if (!decode(r, type) || !r.u8(encoding) || encoding != 1 || !r.i32(length) || length < 0 || !r.bytes(static_cast<size_t>(length), body))
      return broken("a malformed notification in a Publish response");
    if (type != NodeId::num(0, kDataChangeNotificationId)) continue;  // a StatusChangeNotification, events
    Reader items(body);
    uint32_t count = 0;
    if (!items.arrayLength(count, 5)) return broken("a malformed DataChangeNotification");
    for (uint32_t item = 0; item < count; ++item) {
      uint32_t handle = 0;
      RawValue value;
      if (!items.u32(handle) || !readRawValue(items, value) || !value.wholly())
        return broken("a malformed DataChangeNotification");
      if (handle >= slots_.size() || !slots_[handle].found || config_.signals[handle].toPlc)
        return broken("a DataChangeNotification for client handle " + std::to_string(handle) + ", not one of the monitored items");
      if (!takeValue(bus, handle, value)) return false;
    }
  }
  if (notifications > 0) {  // a keep-alive (none) is not acknowledged
    subscription_.ack = subscriptionId == subscription_.id;
    subscription_.ackSequence = sequence;
  }
  return true;
}

}  // namespace virtcom::proto::opcua
