#pragma once
// The client bridge: an external PLC with a Modbus TCP server is the cell's controller. Every
// `poll` of simulated time the bridge reads the PLC tables that hold device commands (merged
// into as few FC1/2/3/4 requests as the map allows) and writes the device status signals whose
// encoding changed since they were last written (FC5/FC6/FC16). Uses libmodbus, blocking, on
// the simulation's thread (bounded by the response timeout).
// Connection loss (refused, reset, timeout) is reported once through `report`; with
// faultOnLoss the next pull() fails and the run ends, otherwise the last commands are held
// and the bridge reconnects at each poll. An exception response (the map names an address the
// PLC does not have) always fails: it is a configuration error, not a lost link.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/bus_bridge.hpp"
#include "proto/modbus/signal_codec.hpp"
#include "proto/modbus/signal_map.hpp"
#include "proto/net/endpoint.hpp"
#include "proto/net/link_loss.hpp"

struct _modbus;

namespace virtcom::proto::modbus {

struct ClientConfig {
  net::Endpoint peer;
  int unit = 1;
  int64_t pollNs = 10'000'000;
  int64_t timeoutNs = 500'000'000;
  bool faultOnLoss = true;
  SignalMap map;                                   // MapRole::Client
  std::function<void(const std::string&)> report;  // connection events, one line each
};

class ClientBridge final : public BusBridge {
 public:
  // A run of consecutive addresses of one table read with one request.
  struct ReadBlock {
    Table table;
    uint16_t address;
    uint16_t count;
  };

  explicit ClientBridge(ClientConfig config);
  ~ClientBridge() override;
  ClientBridge(const ClientBridge&) = delete;
  ClientBridge& operator=(const ClientBridge&) = delete;

  bool pull(TagBus& bus, int64_t nowNs) override;
  void push(const TagBus& bus, int64_t nowNs) override;
  std::string failure() const override { return link_.failure(); }

  // Requests sent and failed so far (for statistics and tests).
  uint64_t requests() const { return requests_; }

 private:
  bool connect();
  void lose(const std::string& what);
  bool readBlock(const ReadBlock& b);
  bool writeEntry(const MapEntry& e);

  ClientConfig config_;
  std::vector<MapEntry> commands_, status_;
  std::vector<ReadBlock> blocks_;
  TableImage mirror_;       // the PLC's tables as last read / about to be written
  TableImage written_;      // status as last written successfully
  std::vector<bool> dirty_;  // per status entry: must be written even if unchanged (after connecting)
  _modbus* ctx_ = nullptr;
  bool connected_ = false;
  net::LinkLoss link_;  // what a lost link or a refusal does to the run (shared with the ADS and OPC UA bridges)
  bool pollNow_ = false;
  int64_t nextPollNs_ = 0;
  uint64_t requests_ = 0;
};

}  // namespace virtcom::proto::modbus
