// Session: device notifications (docs/ads.md, Wire reference: Device notifications).
#include <algorithm>
#include <limits>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/index_group.hpp"
#include "proto/ads/session.hpp"

namespace virtcom::proto::ads {

namespace {

// ADSTRANSMODE (docs/ads.md, Device notifications); the "in context" variants behave like their
// plain ones here.
constexpr uint32_t kServerCycle = 3, kServerOnChange = 4, kServerCycleInContext = 5, kServerOnChangeInContext = 6;
constexpr int64_t kNsPer100Ns = 100;

}  // namespace

AdsError Session::addNotification(std::span<const uint8_t> body, uint32_t& handle) {
  LittleEndianReader in(body);
  uint32_t ig = *in.u32(), io = *in.u32();
  const uint32_t length = *in.u32(), mode = *in.u32();
  in.u32();  // maxDelay: samples go out at once, which honours any maximum delay
  const uint32_t cycle = *in.u32();
  if (mode != kServerCycle && mode != kServerOnChange && mode != kServerCycleInContext && mode != kServerOnChangeInContext)
    return AdsError::TransModeNotSupported;
  if (length == 0 || length == kAnyLength) return AdsError::InvalidSize;
  if (ig == static_cast<uint32_t>(IndexGroup::SymValueByHandle)) {
    // AdsLib's notification by name: IO is a symbol handle (docs/ads.md, Device notifications).
    const Symbol* h = findHandle(io);
    if (!h) return AdsError::SymbolNotFound;
    if (length > h->size) return AdsError::InvalidSize;
    ig = h->indexGroup;
    io = h->indexOffset;
  }
  scratch_.clear();
  if (AdsError e = device_.read(ig, io, length, scratch_); e != AdsError::None) return e;
  if (notifications_.size() >= device_.config().maxNotificationsPerConnection) return AdsError::NoMoreNotificationHandles;
  Notification n;
  n.handle = nextNotificationHandle_;
  nextNotificationHandle_ = nextNotificationHandle_ == std::numeric_limits<uint32_t>::max() ? 1 : nextNotificationHandle_ + 1;
  n.client = currentClient_;
  n.server = currentServer_;
  n.ig = ig;
  n.io = io;
  n.length = length;
  n.onChange = mode == kServerOnChange || mode == kServerOnChangeInContext;
  n.cycleNs = int64_t{cycle} * kNsPer100Ns;
  // Groups like 0xF100 accept any length and answer fewer bytes, and a read past an area's end
  // answers what there is: the sample is what the read answers, so every frame is consistent.
  n.length = static_cast<uint32_t>(scratch_.size());
  n.last.reserve(scratch_.size());
  notifications_.push_back(std::move(n));
  handle = notifications_.back().handle;
  return AdsError::None;
}

AdsError Session::deleteNotification(uint32_t handle) {
  auto it = std::find_if(notifications_.begin(), notifications_.end(), [&](const Notification& n) { return n.handle == handle; });
  if (it == notifications_.end()) return AdsError::NotificationHandleInvalid;
  notifications_.erase(it);
  return AdsError::None;
}

int64_t Session::nextCycleDueNs() const {
  int64_t next = std::numeric_limits<int64_t>::max();
  for (const Notification& n : notifications_)
    if ((!n.sent && n.firstDueSet) || (!n.onChange && n.cycleNs > 0)) next = std::min(next, n.nextCheckNs);
  return next;
}

void Session::sendDueNotifications(int64_t nowNs, uint64_t fileTime, std::vector<uint8_t>& out) {
  for (Notification& n : notifications_) {
    if (!n.firstDueSet) {
      // The first sample waits one task cycle after the reply, as TwinCAT sends it at the end of
      // the next cycle: AdsLib registers its callback only once the reply is in, and a sample
      // in the same segment as the reply is dropped (docs/ads.md, Device notifications).
      n.firstDueSet = true;
      n.nextCheckNs = nowNs + kFirstSampleDelayNs;
    }
    if (nowNs < n.nextCheckNs) continue;
    n.nextCheckNs = nowNs + n.cycleNs;
    value_.clear();
    if (device_.read(n.ig, n.io, n.length, value_) != AdsError::None) continue;
    if (n.onChange && n.sent && value_ == n.last) continue;
    n.last.assign(value_.begin(), value_.end());
    n.sent = true;
    // Stream (docs/ads.md, Device notifications): length = bytes after this field, one stamp
    // with one sample.
    const uint32_t dataLength = 4 + 4 + 8 + 4 + 4 + 4 + n.length;
    AmsHeader h;
    h.target = n.client;
    h.source = n.server;
    h.commandId = static_cast<uint16_t>(Command::DeviceNotification);
    h.stateFlags = state_flags::kNotification;
    h.dataLength = dataLength;
    writeAmsFrameHeader(out, h);
    LittleEndianWriter w(out);
    w.u32(dataLength - 4);
    w.u32(1);
    w.u64(fileTime);
    w.u32(1);
    w.u32(n.handle);
    w.u32(n.length);
    w.bytes(value_);
  }
}

}  // namespace virtcom::proto::ads
