#pragma once
// The OPC UA client bridge: an external PLC with an OPC UA server (CODESYS, TwinCAT TF6100, a
// Siemens PLC, or `virtcom exec --opcua`) is the cell's controller. Every signal names a node, by
// node id or by browse path (browse_path.hpp):
//  - at start (and after each reconnect: a restarted PLC may number its nodes anew) one
//    TranslateBrowsePathsToNodeIds resolves every browse path; each that leads nowhere is a
//    problem of its signal;
//  - at start one Read asks for the Value and UserAccessLevel of every node: its built-in type
//    (checked against the device port) and, for device outputs, that this session may write it;
//    every problem is collected, none is left for the run;
//  - the PLC's outputs (the device commands) are watched by a subscription: one monitored item
//    each, sampled and published every `poll`, pull() taking what the last Publish brought; a
//    server that refuses subscriptions is polled instead, pull() reading them with one Read every
//    `poll` of simulated time;
//  - every `poll` push() writes the device outputs whose value changed since they were last
//    written with one Write;
//  - when the simulation stops, with disconnectWhenStopped the session and channel are closed.
// A lost link (refused, reset, timeout, ERR) fails the next pull() with faultOnLoss; otherwise it
// is reported once, the devices keep the last commands, and each poll tries to reconnect (which
// checks the nodes again and rewrites every device output). A Bad status of a node in a reply (a
// node the server no longer has, a refused write) always fails: the PLC program changed.
// Values cross as their bytes (numbers are little endian on the wire as in the PLC's image, as
// plc_values.cpp serves them); nothing is allocated per poll after start.
#include <cstddef>
#include <cstdint>
#include <expected>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/bus_bridge.hpp"
#include "core/iec_value.hpp"
#include "proto/net/link_loss.hpp"
#include "proto/opcua/browse_path.hpp"
#include "proto/opcua/client.hpp"
#include "proto/opcua/raw_values.hpp"

namespace virtcom::proto::opcua {

struct BridgeSignal {
  std::string node;       // the node id, e.g. "ns=4;s=|var|virtcom.Application.MAIN.Robot1.execute", or a browse path, "/4:MAIN/4:x"
  std::string name;       // what the cell file names (a variable or the node id), for messages
  std::string port;       // what it is wired to, for messages, e.g. "Robot1.execute"
  TagId tag = kNoTag;     // kNoTag: a value only observed (recorded); start() adds its tag
  bool toPlc = false;     // true: a device output written to the PLC; false: read from the PLC
  bool optional = false;  // a missing node is skipped (wiring by prefix), not an error
};

struct BridgeConfig {
  ClientConfig client;
  int64_t pollNs = 10'000'000;
  bool subscribe = true;  // false: read the PLC's outputs every poll even if the server could publish them
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

  // Connects and checks every signal; observed-only signals get a tag of the node's type on
  // `bus`. Null when anything failed; `report` then lists every failure.
  static std::unique_ptr<ClientBridge> start(BridgeConfig config, TagBus& bus, StartReport& report);
  ~ClientBridge() override;

  bool pull(TagBus& bus, int64_t nowNs) override;
  void push(const TagBus& bus, int64_t nowNs) override;
  std::string failure() const override { return link_.failure(); }
  void simulationStopped() override;

  // The tag of signal i (the one start() added for an observed node).
  TagId tag(size_t signal) const { return slots_[signal].tag; }
  // "the OPC UA server at opc.tcp://127.0.0.1:4840".
  std::string peerText() const;
  uint64_t requests() const { return client_.requests(); }
  // How the PLC's outputs come: "a Read every 10 ms" or "subscribed, published every 10 ms".
  std::string updatesText() const;
  bool subscribed() const { return subscription_.id != 0; }

 private:
  // A checked signal: its built-in type, the elementary type its bytes hold, where they are.
  struct Slot {
    bool found = false;   // checked: the server has it, as wired
    bool exists = false;  // the server has a node of that id
    TagId tag = kNoTag;
    BuiltinType wire = BuiltinType::Null;
    ElemType type = ElemType::Bool;
    uint32_t size = 0;
    uint32_t offset = 0;  // in image_ (the values as last read / written)
    bool dirty = true;    // must be written even if unchanged (after connecting)
    bool unresolved = false;  // its browse path led nowhere: not read (a problem already)
  };
  struct PathSignal {
    size_t signal = 0;
    std::vector<BrowsePathElement> path;
  };

  explicit ClientBridge(BridgeConfig config);
  // Reads every node's Value and UserAccessLevel and checks them. False if anything failed
  // (`problems` says what). With addTags, observed-only signals get their tags (start); else
  // the types must not have changed since (reconnecting).
  bool resolve(TagBus& bus, bool addTags, std::vector<Problem>& problems);
  // Resolves every browse path into nodeIds_ with one TranslateBrowsePathsToNodeIds
  // (client_bridge_paths.cpp); a path that leads nowhere is its signal's problem (or skipped if
  // optional) and its slot unresolved. False only if the connection failed (`problems` says how).
  bool translatePaths(std::vector<Problem>& problems);
  bool reconnect(TagBus& bus);
  void lose(const std::string& what);
  // Polls the PLC's outputs with one Read (pull() without a subscription).
  bool readOutputs(TagBus& bus);
  // One value of the PLC's output i onto the bus; false (refused) if Bad or not of its type.
  bool takeValue(TagBus& bus, size_t i, const RawValue& value);

  // The subscription (client_bridge_subscription.cpp): one with a monitored item per PLC output,
  // one Publish always posted, its notifications taken by pull(). A server that refuses it (or
  // an item) is polled with Read instead. An error is a lost link (its text).
  std::expected<void, std::string> subscribe();
  void pollInstead(const std::string& why);
  bool takePublished(TagBus& bus);
  bool postPublish();
  bool takeNotifications(TagBus& bus, Reader& r);
  struct SubscriptionState {
    uint32_t id = 0;           // 0: none, the outputs are read
    double intervalMs = 0;     // the publishing interval, as revised
    int64_t silenceNs = 0;     // no Publish answered for that long: a lost link
    int64_t answerByNs = 0;    // the posted Publish's
    bool ack = false;          // acknowledge ackSequence with the next Publish
    uint32_t ackSequence = 0;
  };

  BridgeConfig config_;
  Client client_;
  net::LinkLoss link_;  // after config_: built from it
  std::vector<Slot> slots_;
  std::vector<std::vector<uint8_t>> nodeIds_;  // each signal's NodeId, encoded once (a path's: when resolved)
  std::vector<PathSignal> paths_;              // the signals named by browse path
  std::vector<size_t> reads_, writes_;         // signals read each poll / written on change
  std::vector<uint8_t> image_;                 // one value per found signal
  std::vector<size_t> changed_;                // signals written this poll (capacity reserved)
  SubscriptionState subscription_;
  bool pollNow_ = false;
  int64_t nextPollNs_ = 0;
};

}  // namespace virtcom::proto::opcua
