// CreateSubscription, ModifySubscription, SetPublishingMode, DeleteSubscriptions,
// CreateMonitoredItems, DeleteMonitoredItems, Publish, Republish, and the publishing cycle the
// channel runs (docs/opcua.md, Subscriptions; OPC 10000-4 §5.12, §5.13, §5.14).
#include <algorithm>
#include <cmath>

#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kDecodingError = static_cast<uint32_t>(StatusCodeValue::BadDecodingError);
constexpr uint32_t bad(StatusCodeValue v) { return static_cast<uint32_t>(v); }
constexpr uint32_t kBadSubscriptionIdInvalid = 0x80280000, kBadMonitoredItemIdInvalid = 0x80420000,
                   kBadTooManySubscriptions = 0x80770000, kBadTooManyMonitoredItems = 0x80DB0000,
                   kBadTooManyPublishRequests = 0x80780000, kBadNoSubscription = 0x80790000,
                   kBadMessageNotAvailable = 0x807B0000, kBadSequenceNumberUnknown = 0x807A0000,
                   kBadMonitoredItemFilterUnsupported = 0x80440000;
// Encoding ids: DataChangeNotification 811, DataChangeFilter 724, PublishResponse 829.
constexpr uint32_t kDataChangeNotificationId = 811, kDataChangeFilterId = 724, kPublishResponseId = 829;
constexpr uint32_t kDeadbandAbsolute = 1;
// Intervals the server grants (ms): sampling and publishing no faster than 1 ms (its I/O thread
// then wakes 1000 times a second while such a subscription lives: docs/performance.md).
constexpr double kMinIntervalMs = 1, kMaxIntervalMs = 3'600'000;
constexpr uint32_t kMaxQueueSize = 1000;

int64_t toNs(double ms) { return static_cast<int64_t>(ms * 1e6); }
double reviseInterval(double ms) { return std::isnan(ms) || ms < kMinIntervalMs ? kMinIntervalMs : std::min(ms, kMaxIntervalMs); }

Subscription* findSubscription(Session& s, uint32_t id) {
  auto it = std::find_if(s.subscriptions.begin(), s.subscriptions.end(), [id](const Subscription& x) { return x.id == id; });
  return it == s.subscriptions.end() ? nullptr : &*it;
}

// Keep-alive at least 1; lifetime at least three keep-alives (OPC 10000-4 §5.13.2.2).
void reviseCounts(Subscription& sub, uint32_t lifetime, uint32_t keepAlive) {
  sub.keepAliveCount = std::clamp<uint32_t>(keepAlive, 1, 10000);
  sub.lifetimeCount = std::max<uint32_t>(lifetime, 3 * sub.keepAliveCount);
}

// The number a scalar Variant holds (for the deadband); false if it is not a number.
bool numberOf(std::span<const uint8_t> variant, double& out) {
  Reader r(variant);
  Variant v;
  if (!decode(r, v) || v.isArray || v.values.size() != 1) return false;
  return std::visit(
      [&out](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
          out = static_cast<double>(x);
          return true;
        }
        return false;
      },
      v.values[0]);
}

// Samples one item: queues a DataValue if the value changed (beyond the deadband).
void sample(ServerCore& core, MonitoredItem& item, std::vector<uint8_t>& scratch) {
  scratch.clear();
  Writer w(scratch);
  const uint32_t status = encodeValueAttribute(w, core, core.space().node(item.node));
  if (status != 0) return;
  if (item.sampled && scratch == item.last) return;
  double number = 0;
  const bool numeric = item.deadband > 0 && numberOf(scratch, number);
  if (item.sampled && numeric && std::fabs(number - item.lastNumber) <= item.deadband) return;
  item.sampled = true;
  item.last = scratch;
  item.lastNumber = number;
  std::vector<uint8_t> value;
  Writer dv(value);
  dv.u8(kDataValueValue | kDataValueSourceTime | kDataValueServerTime);
  dv.raw(scratch);
  const DateTime now = dateTimeNow();
  encode(dv, now);
  encode(dv, now);
  if (item.queue.size() >= item.queueSize) {
    if (item.discardOldest) item.queue.pop_front();
    else item.queue.pop_back();
  }
  item.queue.push_back(std::move(value));
}

bool hasNotifications(const Subscription& sub) {
  return std::any_of(sub.items.begin(), sub.items.end(), [](const MonitoredItem& i) { return !i.queue.empty(); });
}

// A NotificationMessage: sequence number, publish time, the DataChangeNotification (or none:
// a keep-alive, which carries the next sequence number without using it).
void encodeNotificationMessage(Writer& w, Subscription& sub, bool keepAlive) {
  const size_t start = w.size();
  w.u32(sub.nextSequence);
  encode(w, dateTimeNow());
  if (keepAlive) {
    w.i32(0);
    return;
  }
  w.i32(1);
  encode(w, NodeId::num(0, kDataChangeNotificationId));
  w.u8(static_cast<uint8_t>(ExtensionObject::Body::Binary));
  const size_t lengthAt = w.size();
  w.i32(0);
  const size_t countAt = w.size();
  w.i32(0);
  uint32_t count = 0;
  for (auto& item : sub.items) {
    while (!item.queue.empty() && (sub.maxNotifications == 0 || count < sub.maxNotifications)) {
      w.u32(item.clientHandle);
      w.raw(item.queue.front());
      item.queue.pop_front();
      ++count;
    }
  }
  w.put32(countAt, count);
  w.i32(0);  // DiagnosticInfos
  w.put32(lengthAt, static_cast<uint32_t>(w.size() - lengthAt - 4));
  sub.lastSequence = sub.nextSequence++;
  sub.lastMessage.assign(w.buffer().begin() + static_cast<ptrdiff_t>(start), w.buffer().end());
}

}  // namespace

uint32_t handleCreateSubscription(ServiceContext& ctx, Reader& in, Writer& out) {
  double interval = 0;
  uint32_t lifetime = 0, keepAlive = 0, maxNotifications = 0;
  bool enabled = true;
  uint8_t priority = 0;
  if (!decode(in, interval) || !in.u32(lifetime) || !in.u32(keepAlive) || !in.u32(maxNotifications) || !decode(in, enabled) ||
      !in.u8(priority))
    return kDecodingError;
  Session& s = *ctx.session;
  if (s.subscriptions.size() >= ctx.core.config().maxSubscriptions) return kBadTooManySubscriptions;
  Subscription sub;
  sub.id = ctx.core.newSubscriptionId();
  interval = reviseInterval(interval);
  sub.publishingNs = toNs(interval);
  sub.nextPublishNs = ctx.nowNs + sub.publishingNs;
  sub.maxNotifications = maxNotifications;
  sub.enabled = enabled;
  reviseCounts(sub, lifetime, keepAlive);
  out.u32(sub.id);
  encode(out, interval);
  out.u32(sub.lifetimeCount);
  out.u32(sub.keepAliveCount);
  s.subscriptions.push_back(std::move(sub));
  return 0;
}

uint32_t handleModifySubscription(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t id = 0, lifetime = 0, keepAlive = 0, maxNotifications = 0;
  double interval = 0;
  uint8_t priority = 0;
  if (!in.u32(id) || !decode(in, interval) || !in.u32(lifetime) || !in.u32(keepAlive) || !in.u32(maxNotifications) || !in.u8(priority))
    return kDecodingError;
  Subscription* sub = findSubscription(*ctx.session, id);
  if (!sub) return kBadSubscriptionIdInvalid;
  interval = reviseInterval(interval);
  sub->publishingNs = toNs(interval);
  sub->maxNotifications = maxNotifications;
  reviseCounts(*sub, lifetime, keepAlive);
  encode(out, interval);
  out.u32(sub->lifetimeCount);
  out.u32(sub->keepAliveCount);
  return 0;
}

uint32_t handleSetPublishingMode(ServiceContext& ctx, Reader& in, Writer& out) {
  bool enabled = false;
  uint32_t count = 0;
  if (!decode(in, enabled) || !in.arrayLength(count, 4)) return kDecodingError;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  out.i32(static_cast<int32_t>(count));
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t id = 0;
    if (!in.u32(id)) return kDecodingError;
    Subscription* sub = findSubscription(*ctx.session, id);
    if (sub) sub->enabled = enabled;
    out.u32(sub ? 0 : kBadSubscriptionIdInvalid);
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleDeleteSubscriptions(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t count = 0;
  if (!in.arrayLength(count, 4)) return kDecodingError;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  auto& subs = ctx.session->subscriptions;
  out.i32(static_cast<int32_t>(count));
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t id = 0;
    if (!in.u32(id)) return kDecodingError;
    const size_t before = subs.size();
    std::erase_if(subs, [id](const Subscription& s) { return s.id == id; });
    out.u32(subs.size() < before ? 0 : kBadSubscriptionIdInvalid);
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleCreateMonitoredItems(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t id = 0, timestamps = 0, count = 0;
  if (!in.u32(id) || !in.u32(timestamps) || !in.arrayLength(count, 20)) return kDecodingError;
  Subscription* sub = findSubscription(*ctx.session, id);
  if (!sub) return kBadSubscriptionIdInvalid;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  out.i32(static_cast<int32_t>(count));
  std::vector<uint8_t> scratch;
  for (uint32_t i = 0; i < count; ++i) {
    NodeId nodeId;
    uint32_t attribute = 0, mode = 0, clientHandle = 0, queueSize = 0;
    String indexRange;
    QualifiedName encoding;
    double samplingMs = 0;
    ExtensionObject filter;
    bool discardOldest = true;
    if (!decode(in, nodeId) || !in.u32(attribute) || !decode(in, indexRange) || !decode(in, encoding) || !in.u32(mode) ||
        !in.u32(clientHandle) || !decode(in, samplingMs) || !decode(in, filter) || !in.u32(queueSize) || !decode(in, discardOldest))
      return kDecodingError;
    auto node = ctx.core.space().find(nodeId);
    uint32_t status = 0;
    double deadband = 0;
    if (!node) status = bad(StatusCodeValue::BadNodeIdUnknown);
    else if (attribute != kValueAttr || ctx.core.space().node(*node).nodeClass != NodeClass::Variable)
      status = bad(StatusCodeValue::BadAttributeIdInvalid);
    else if (sub->items.size() >= ctx.core.config().maxMonitoredItems) status = kBadTooManyMonitoredItems;
    else if (filter.typeId == NodeId::num(0, kDataChangeFilterId)) {
      Reader f(filter.view());
      uint32_t trigger = 0, deadbandType = 0;
      if (!f.u32(trigger) || !f.u32(deadbandType) || !decode(f, deadband)) return kDecodingError;
      if (deadbandType > kDeadbandAbsolute || deadband < 0) status = kBadMonitoredItemFilterUnsupported;
      if (deadbandType == 0) deadband = 0;
    } else if (!filter.typeId.isNull()) {
      status = kBadMonitoredItemFilterUnsupported;
    }
    if (status != 0) {
      out.u32(status);
      out.u32(0);
      encode(out, 0.0);
      out.u32(0);
      encode(out, ExtensionObject{});
      continue;
    }
    MonitoredItem item;
    item.id = sub->nextItemId++;
    item.clientHandle = clientHandle;
    item.node = *node;
    // A negative interval means "the publishing interval"; 0 the fastest the server samples.
    const double revised = samplingMs < 0 ? static_cast<double>(sub->publishingNs) / 1e6 : reviseInterval(samplingMs);
    item.samplingNs = toNs(revised);
    item.nextSampleNs = ctx.nowNs + item.samplingNs;
    item.queueSize = std::clamp<uint32_t>(queueSize, 1, kMaxQueueSize);
    item.discardOldest = discardOldest;
    item.deadband = deadband;
    sample(ctx.core, item, scratch);  // the first value is reported at once
    out.u32(0);
    out.u32(item.id);
    encode(out, revised);
    out.u32(item.queueSize);
    encode(out, ExtensionObject{});
    sub->items.push_back(std::move(item));
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleDeleteMonitoredItems(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t id = 0, count = 0;
  if (!in.u32(id) || !in.arrayLength(count, 4)) return kDecodingError;
  Subscription* sub = findSubscription(*ctx.session, id);
  if (!sub) return kBadSubscriptionIdInvalid;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  out.i32(static_cast<int32_t>(count));
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t itemId = 0;
    if (!in.u32(itemId)) return kDecodingError;
    const size_t before = sub->items.size();
    std::erase_if(sub->items, [itemId](const MonitoredItem& m) { return m.id == itemId; });
    out.u32(sub->items.size() < before ? 0 : kBadMonitoredItemIdInvalid);
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handlePublish(ServiceContext& ctx, Reader& in, Writer&) {
  uint32_t count = 0;
  if (!in.arrayLength(count, 8)) return kDecodingError;
  Session& s = *ctx.session;
  PendingPublish p{ctx.requestId, ctx.requestHandle, {}};
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t id = 0, sequence = 0;
    if (!in.u32(id) || !in.u32(sequence)) return kDecodingError;
    // Only the last message is retained: acknowledging it (or an older one) frees nothing else.
    Subscription* sub = findSubscription(s, id);
    p.ackResults.push_back(!sub ? kBadSubscriptionIdInvalid : sequence <= sub->lastSequence ? 0 : kBadSequenceNumberUnknown);
  }
  if (s.subscriptions.empty()) return kBadNoSubscription;
  if (s.publishes.size() >= ctx.core.config().maxPublishRequests) return kBadTooManyPublishRequests;
  s.publishes.push_back(std::move(p));
  return kDeferredResponse;
}

uint32_t handleRepublish(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t id = 0, sequence = 0;
  if (!in.u32(id) || !in.u32(sequence)) return kDecodingError;
  Subscription* sub = findSubscription(*ctx.session, id);
  if (!sub) return kBadSubscriptionIdInvalid;
  if (sequence == 0 || sequence != sub->lastSequence || sub->lastMessage.empty()) return kBadMessageNotAvailable;
  out.raw(sub->lastMessage);
  return 0;
}

int64_t nextSubscriptionDueNs(const Session& session) {
  int64_t due = INT64_MAX;
  for (const Subscription& sub : session.subscriptions) {
    due = std::min(due, sub.nextPublishNs);
    for (const MonitoredItem& item : sub.items) due = std::min(due, item.nextSampleNs);
  }
  return due;
}

void runSubscriptions(ServerCore& core, Session& session, int64_t nowNs, std::vector<uint8_t>& body,
                      const std::function<void(uint32_t)>& send) {
  std::vector<uint8_t> scratch;
  for (size_t k = 0; k < session.subscriptions.size();) {
    Subscription& sub = session.subscriptions[k];
    for (MonitoredItem& item : sub.items) {
      if (nowNs < item.nextSampleNs) continue;
      sample(core, item, scratch);
      item.nextSampleNs = std::max(item.nextSampleNs + item.samplingNs, nowNs);
    }
    if (nowNs < sub.nextPublishNs) {
      ++k;
      continue;
    }
    sub.nextPublishNs = std::max(sub.nextPublishNs + sub.publishingNs, nowNs);
    const bool notify = sub.enabled && hasNotifications(sub);
    const bool keepAlive = !notify && ++sub.keepAliveCounter >= sub.keepAliveCount;
    if ((notify || keepAlive) && !session.publishes.empty()) {
      PendingPublish p = std::move(session.publishes.front());
      session.publishes.pop_front();
      body.clear();
      Writer w(body);
      encode(w, NodeId::num(0, kPublishResponseId));
      encode(w, dateTimeNow());  // ResponseHeader
      w.u32(p.requestHandle);
      w.u32(0);
      w.u8(0);
      w.i32(0);
      encode(w, ExtensionObject{});
      w.u32(sub.id);
      const size_t availableAt = w.size();
      w.i32(0);  // AvailableSequenceNumbers: patched below
      w.u8(0);   // MoreNotifications
      encodeNotificationMessage(w, sub, !notify);
      w.i32(static_cast<int32_t>(p.ackResults.size()));
      for (uint32_t r : p.ackResults) w.u32(r);
      encodeNoDiagnostics(w);
      if (sub.lastSequence != 0) {
        // One retained message: insert its number into the (empty) array written above.
        uint8_t number[4];
        for (int i = 0; i < 4; ++i) number[i] = static_cast<uint8_t>(sub.lastSequence >> (8 * i));
        body.insert(body.begin() + static_cast<ptrdiff_t>(availableAt + 4), number, number + 4);
        w.put32(availableAt, 1);
      }
      sub.keepAliveCounter = 0;
      sub.lifetimeCounter = 0;
      send(p.requestId);
    } else if ((notify || keepAlive) && ++sub.lifetimeCounter >= sub.lifetimeCount) {
      // No Publish request for the whole lifetime: the client is gone.
      session.subscriptions.erase(session.subscriptions.begin() + static_cast<ptrdiff_t>(k));
      continue;
    }
    ++k;
  }
}

}  // namespace virtcom::proto::opcua
