#pragma once
// The PLC as ADS clients see it, shared by every connection: the symbol table, the last published
// memory snapshot, the queue of writes for the next scan and the RUN/STOP state.
// Not thread-safe: the server holds one mutex around every call (see server.hpp).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "proto/ads/ams.hpp"
#include "proto/ads/handle_table.hpp"
#include "proto/ads/symbol_table.hpp"
#include "proto/ads/write_queue.hpp"

namespace virtcom::proto::ads {

// ADS states (docs/ads.md, Wire reference: States and return codes).
inline constexpr uint16_t kAdsStateReset = 2, kAdsStateRun = 5, kAdsStateStop = 6, kAdsStateError = 11;
// AMS ports served (docs/ads.md, AMS/TCP and the AMS header).
inline constexpr uint16_t kPlcPort = 851, kSystemPort = 10000;

struct DeviceConfig {
  AmsNetId netId{127, 0, 0, 1, 1, 1};
  bool readOnly = false;                  // every write and WriteControl refused (0x704)
  size_t writeQueueBytes = 64 * 1024;     // queued write data between two scans; beyond: 0x708
  size_t maxHandlesPerRoute = 10000;            // per AMS route (NetId:port); beyond: 0x70A
  size_t maxHandleRoutes = 256;                 // routes holding handles at once; beyond: 0x70A
  size_t maxNotificationsPerConnection = 1000;   // beyond: 0x716
  size_t maxSumItems = 4096;                     // sub-commands of one sum command; beyond: 0x706
  size_t maxSumReadBytes = 1024 * 1024;          // data of one sum read reply; beyond: 0x705
};

// A RUN or STOP a client asked for (WriteControl), and who asked (audited when the scan takes it).
struct StateRequest {
  uint16_t adsState = kAdsStateRun;
  ExternalWriter writer;
  bool operator==(const StateRequest&) const = default;
};

class Device {
 public:
  Device(const SymbolTable& table, DeviceConfig config);

  const SymbolTable& table() const { return table_; }
  const DeviceConfig& config() const { return config_; }

  // Appends the data a Read of (ig, io, length) returns: at most `length` bytes (0xFFFFFFFF: all
  // there is). Covers the memory groups, the upload services and the state groups; handles are
  // the session's business. Nothing is appended on error.
  AdsError read(uint32_t ig, uint32_t io, uint32_t length, std::vector<uint8_t>& out) const;
  // Checks a Write of (ig, io, data) whole, then queues it for the next scan and applies it to
  // the snapshot (so it reads back at once).
  AdsError write(uint32_t ig, uint32_t io, std::span<const uint8_t> data);

  // WriteControl on port 851: RUN (5) or STOP (6), asked for by `writer`.
  AdsError requestState(uint16_t adsState, const ExternalWriter& writer);
  uint16_t adsState() const { return adsState_; }
  uint8_t symbolVersion() const { return symbolVersion_; }
  std::span<const uint8_t> snapshot() const { return snapshot_; }

  // Scan side (under the server's lock): see Server.
  std::optional<StateRequest> takeStateRequest();
  void publish(std::span<const uint8_t> image, uint16_t adsState);
  WriteQueue& pendingWrites() { return pending_; }
  // Symbol handles, per AMS route: they outlive connections (handle_table.hpp).
  HandleTable& handles() { return handles_; }

  // A fresh client port for AMS/TCP port registration (0x1000).
  uint16_t assignPort();

 private:
  // The data-area range an index group's bytes or bits map to, or nullptr for other groups.
  const ByteRange* areaOf(uint32_t ig) const;
  AdsError readBits(const ByteRange& area, uint32_t bitAddress, uint32_t length, std::vector<uint8_t>& out) const;
  AdsError writeBits(const ByteRange& area, uint32_t bitAddress, std::span<const uint8_t> data);

  const SymbolTable& table_;
  DeviceConfig config_;
  ByteRange dataArea_;
  std::vector<uint8_t> snapshot_;
  std::vector<uint8_t> symbolUpload_, typeUpload_;
  uint32_t typeCount_ = 0;
  WriteQueue pending_;
  HandleTable handles_;
  uint16_t adsState_ = kAdsStateRun;
  std::optional<StateRequest> requestedState_;
  uint8_t symbolVersion_ = 1;
  uint16_t nextPort_ = 30000;
};

}  // namespace virtcom::proto::ads
