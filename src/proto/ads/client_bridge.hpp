#pragma once
// The ADS client bridge (the seed's PLC_Beckhoff component): an external PLC reached over ADS
// (a TwinCAT 3 runtime, or `virtcom exec --ads`) is the cell's controller. Every signal names a
// PLC variable (`MAIN.Robot1.execute`):
//  - at start each is looked up by name (symbol info 0xF009: type and size, checked against the
//    device port) and gets a handle (0xF003); every problem is collected, none is left for the run;
//  - every step pull() reads the PLC's outputs (the device commands) with one sum read (0xF080)
//    and push() writes the device outputs whose value changed since they were last written (one
//    Write, or one sum write 0xF081 when several changed);
//  - when the simulation stops, with disconnectWhenStopped the handles are released (a sum
//    write of 0xF006) and the connection closed.
// A lost link (refused, reset, timeout) fails the next pull() with faultOnLoss; otherwise it is
// reported once, the devices keep the last commands, and each step tries to reconnect (which
// resolves the handles again and rewrites every device output). An ADS error in a reply (a
// handle the PLC no longer knows, a refused write) always fails: the PLC program changed.
// Blocking, on the simulation's thread; nothing is allocated per step after start.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/bus_bridge.hpp"
#include "core/iec_value.hpp"
#include "proto/net/link_loss.hpp"
#include "proto/ads/byte_io.hpp"
#include "proto/ads/client.hpp"

namespace virtcom::proto::ads {

struct BridgeSignal {
  std::string variable;   // the PLC variable, e.g. "MAIN.Robot1.execute"
  std::string port;       // what it is wired to, for messages, e.g. "Robot1.execute"
  TagId tag = kNoTag;     // kNoTag: a variable only observed (recorded); start() adds its tag
  bool toPlc = false;     // true: a device output written to the PLC; false: read from the PLC
  bool optional = false;  // a missing variable is skipped (wiring by prefix), not an error
};

struct BridgeConfig {
  ClientConfig client;
  bool faultOnLoss = true;
  bool disconnectWhenStopped = true;
  std::vector<BridgeSignal> signals;
  std::function<void(const std::string&)> report;  // connection events, one line each
};

class ClientBridge final : public BusBridge {
 public:
  static constexpr size_t kNoSignal = net::kNoSignal;
  using Problem = net::SignalProblem;
  using StartReport = net::BridgeStartReport;

  // Connects and resolves every signal; observed-only signals get a tag of the variable's type
  // on `bus`. Null when anything failed; `report` then lists every failure.
  static std::unique_ptr<ClientBridge> start(BridgeConfig config, TagBus& bus, StartReport& report);
  ~ClientBridge() override;

  bool pull(TagBus& bus, int64_t nowNs) override;
  void push(const TagBus& bus, int64_t nowNs) override;
  std::string failure() const override { return link_.failure(); }
  void simulationStopped() override;

  // The tag of signal i (the one start() added for an observed variable).
  TagId tag(size_t signal) const { return slots_[signal].tag; }
  // "the PLC at 127.0.0.1:48898 (AmsNetId 127.0.0.1.1.1, port 851)".
  std::string peerText() const;
  uint64_t requests() const { return client_.requests(); }

 private:
  // A resolved signal: its handle, its type on the PLC, and where its bytes are in the images.
  struct Slot {
    bool found = false;   // resolved: the PLC has it, as wired, with a handle
    bool exists = false;  // the PLC has a variable of that name
    TagId tag = kNoTag;
    ElemType type = ElemType::Bool;
    uint32_t size = 0;
    uint32_t handle = 0;
    uint32_t offset = 0;  // in image_ (the PLC's values as last read / written)
    bool dirty = true;    // must be written even if unchanged (after connecting)
  };

  explicit ClientBridge(BridgeConfig config);
  // Looks every signal up and gets its handles. False if anything failed (`problems` says what).
  // With addTags, observed-only signals get their tags (start); else the types must not have
  // changed since (reconnecting).
  bool resolve(TagBus& bus, bool addTags, std::vector<Problem>& problems);
  void releaseHandles();
  bool reconnect(TagBus& bus);
  void lose(const std::string& what);
  void writeSumHeaders(LittleEndianWriter& w, const std::vector<size_t>& slots) const;

  BridgeConfig config_;
  Client client_;
  net::LinkLoss link_;  // after config_: built from it
  std::vector<Slot> slots_;
  std::vector<size_t> reads_, writes_;  // signals read each step / written on change
  std::vector<uint8_t> image_;          // one value per found signal
  std::vector<uint8_t> readRequest_;    // the sum read, built once per connection
  std::vector<uint8_t> writeRequest_;   // the sum write, rebuilt each step in its capacity
  std::vector<size_t> changed_;         // signals written this step (capacity reserved)
};

}  // namespace virtcom::proto::ads
