#include "proto/modbus/signal_server.hpp"

namespace virtcom::proto::modbus {

std::expected<std::unique_ptr<SignalServer>, std::string> SignalServer::start(const ServerConfig& config, const SignalMap& map) {
  auto server = Server::start(config, tablesFor(map));
  if (!server) return std::unexpected(server.error());
  return std::unique_ptr<SignalServer>(new SignalServer(map, std::move(*server)));
}

SignalServer::SignalServer(const SignalMap& map, std::unique_ptr<Server> server)
    : tables_(tablesFor(map)), server_(std::move(server)) {
  for (const MapEntry& e : map.entries) (e.dir == SignalDir::Command ? commands_ : status_).push_back(e);
}

bool SignalServer::pull(TagBus& bus, int64_t nowNs) {
  if (audit_) audit_->setVirtualTime(nowNs);
  // Only client writes change command tables, so they are decoded only after one.
  if (server_->applyPendingWrites(tables_.view(), audit_) > 0 || !loaded_) {
    for (const MapEntry& e : commands_) loadSignal(e, tables_.view(), bus);
    loaded_ = true;
  }
  return true;
}

void SignalServer::push(const TagBus& bus, int64_t) {
  for (const MapEntry& e : status_) storeSignal(e, bus, tables_.view());
  server_->publishSnapshot(tables_.view());
}

}  // namespace virtcom::proto::modbus
