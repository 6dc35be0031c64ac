#pragma once
// Subscriptions and their monitored items (OPC 10000-4 §5.12, §5.13; docs/opcua.md,
// Subscriptions): the state a session keeps, and the publishing cycle the channel runs on its
// connection's timer. Values are sampled on each item's sampling interval from the published
// image (the same bytes a Read answers), queued when they change (by more than an absolute
// deadband), and sent in PublishResponses queued by the client; keep-alives and the lifetime
// count follow the specification's state machine, simplified to one message per cycle.
#include <cstdint>
#include <deque>
#include <vector>

namespace virtcom::proto::opcua {

struct MonitoredItem {
  uint32_t id = 0, clientHandle = 0, node = 0;
  int64_t samplingNs = 0, nextSampleNs = 0;
  uint32_t queueSize = 1;
  bool discardOldest = true;
  double deadband = 0;        // absolute; 0: any change
  bool sampled = false;       // `last` holds a value
  std::vector<uint8_t> last;  // the Variant last queued (encoded)
  double lastNumber = 0;      // its number, for the deadband
  std::deque<std::vector<uint8_t>> queue;  // DataValues waiting for a Publish
};

struct Subscription {
  uint32_t id = 0;
  int64_t publishingNs = 0, nextPublishNs = 0;
  uint32_t lifetimeCount = 0, keepAliveCount = 0, maxNotifications = 0;
  uint32_t keepAliveCounter = 0, lifetimeCounter = 0;
  bool enabled = true;
  uint32_t nextSequence = 1;
  uint32_t nextItemId = 1;
  std::vector<MonitoredItem> items;
  // The last NotificationMessage sent, for Republish (one retained).
  uint32_t lastSequence = 0;
  std::vector<uint8_t> lastMessage;
};

// A Publish request waiting for a notification or keep-alive.
struct PendingPublish {
  uint32_t requestId = 0, requestHandle = 0;
  std::vector<uint32_t> ackResults;  // one per SubscriptionAcknowledgement
};

}  // namespace virtcom::proto::opcua
