#pragma once
// One client connection's protocol state: its notifications (symbol handles belong to the
// client's AMS route, kept by the device), and the answers to its frames. Pure (no sockets): the server feeds it frames and sends what it
// appends; tests and the fuzz target drive it directly. Not thread-safe: the server calls it
// with the device lock held.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "proto/ads/ams.hpp"
#include "proto/ads/device.hpp"

namespace virtcom::proto::ads {

// A new notification's first sample goes out this long after the AddDeviceNotification reply:
// TwinCAT's default PLC task cycle (docs/ads.md, Device notifications).
inline constexpr int64_t kFirstSampleDelayNs = 10'000'000;

class Session {
 public:
  // `allowedNetIds` empty: any source NetId (no route check on localhost: docs/ads.md, Routes).
  explicit Session(Device& device, std::vector<AmsNetId> allowedNetIds = {});
  // The TCP peer this session answers (for the write audit; the AmsNetId comes with each packet).
  void setPeer(uint32_t ipv4, uint16_t port) {
    writer_.ipv4 = ipv4;
    writer_.port = port;
  }

  // Answers one complete frame (as scanFrame found it), appending the response to `out`.
  // Returns false when the connection must close: AMS/TCP port close, or a source NetId that
  // is not allowed (TwinCAT drops a connection without a route the same way). `withinRate`
  // false: the client exceeds its request rate and the request is answered with 0x708 (busy).
  bool handleFrame(std::span<const uint8_t> frame, std::vector<uint8_t>& out, bool withinRate = true);
  // The connection closed: an AMS port this router registered for it (AMS/TCP port connect, as
  // ads-client does) dies with it, and so do that route's handles. Routes of clients with their
  // own router (AdsLib, TwinCAT) keep theirs (handle_table.hpp).
  void end();

  // Appends one DeviceNotification frame (docs/ads.md, Device notifications) per notification
  // that is due at `nowNs` (monotonic): a new one (its initial sample, kFirstSampleDelayNs after
  // the first call that sees it), a cyclic one whose cycle
  // elapsed, an on-change one whose value differs from the last sent (checked at most once per
  // cycle).
  void sendDueNotifications(int64_t nowNs, uint64_t fileTime, std::vector<uint8_t>& out);
  // Monotonic time at which a cyclic notification is next due; INT64_MAX if none.
  int64_t nextCycleDueNs() const;
  size_t notificationCount() const { return notifications_.size(); }

 private:
  struct Notification {
    uint32_t handle = 0;
    AmsAddress client, server;  // DeviceNotification target / source (docs/ads.md, Device notifications)
    uint32_t ig = 0, io = 0, length = 0;
    bool onChange = true;
    int64_t cycleNs = 0;
    int64_t nextCheckNs = 0;
    bool sent = false;
    bool firstDueSet = false;  // nextCheckNs holds the first sample's time
    std::vector<uint8_t> last;
  };

  void answerPacket(const AmsHeader& h, std::span<const uint8_t> data, std::vector<uint8_t>& out, bool withinRate);
  AdsError plcCommand(const AmsHeader& h, std::span<const uint8_t> data);
  AdsError systemCommand(const AmsHeader& h, std::span<const uint8_t> data);

  // The services; each appends its reply data to `reply` only on success.
  AdsError read(uint32_t ig, uint32_t io, uint32_t length, std::vector<uint8_t>& reply);
  AdsError write(uint32_t ig, uint32_t io, std::span<const uint8_t> data);
  AdsError readWrite(uint32_t ig, uint32_t io, uint32_t readLength, std::span<const uint8_t> data,
                     std::vector<uint8_t>& reply, bool inSum);
  AdsError symbolService(uint32_t ig, uint32_t readLength, std::span<const uint8_t> name, std::vector<uint8_t>& reply);
  AdsError sumRead(uint32_t n, uint32_t readLength, std::span<const uint8_t> data, std::vector<uint8_t>& reply);
  AdsError sumWrite(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply);
  AdsError sumReadWrite(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply);
  AdsError sumAddNotifications(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply);
  AdsError sumDeleteNotifications(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply);
  AdsError addNotification(std::span<const uint8_t> body, uint32_t& handle);
  AdsError deleteNotification(uint32_t handle);

  // The symbol behind one of the current client route's handles (handle_table.hpp).
  const Symbol* findHandle(uint32_t handle) const { return device_.handles().find(currentClient_, handle); }

  Device& device_;
  std::vector<AmsNetId> allowedNetIds_;
  std::vector<Notification> notifications_;
  uint32_t nextNotificationHandle_ = 1;
  AmsAddress currentClient_, currentServer_;  // addresses of the request being answered
  ExternalWriter writer_{WriteProtocol::Ads};   // the peer, as its writes are audited
  std::optional<AmsAddress> registered_;       // the AMS port registered by this connection
  std::vector<uint8_t> reply_, scratch_, value_;
};

}  // namespace virtcom::proto::ads
