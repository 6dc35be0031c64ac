#pragma once
// A served cell: the Modbus server over a signal map, as a bridge the simulation steps. Every
// tick, pull() applies the writes clients made since the last tick and loads the command
// signals from the tables; push() stores the status signals and publishes the tables that
// requests are answered from (see server.hpp for the threading).
#include <expected>
#include <memory>
#include <string>
#include <vector>

#include "core/bus_bridge.hpp"
#include "core/write_audit.hpp"
#include "proto/modbus/server.hpp"
#include "proto/modbus/signal_codec.hpp"
#include "proto/modbus/signal_map.hpp"

namespace virtcom::proto::modbus {

class SignalServer final : public BusBridge {
 public:
  // Starts the server (binds, spawns its I/O thread). Error text if it cannot.
  static std::expected<std::unique_ptr<SignalServer>, std::string> start(const ServerConfig& config, const SignalMap& map);

  // Clients' writes are reported to `audit` (names: auditedSignals of the map) as they land.
  void auditWrites(WriteAudit* audit) { audit_ = audit; }

  bool pull(TagBus& bus, int64_t nowNs) override;
  void push(const TagBus& bus, int64_t nowNs) override;
  Endpoint endpoint() const { return server_->endpoint(); }

 private:
  SignalServer(const SignalMap& map, std::unique_ptr<Server> server);

  std::vector<MapEntry> commands_, status_;
  TableImage tables_;
  std::unique_ptr<Server> server_;
  bool loaded_ = false;
  WriteAudit* audit_ = nullptr;
};

}  // namespace virtcom::proto::modbus
