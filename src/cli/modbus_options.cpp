#include "cli/modbus_options.hpp"

#include <iostream>

namespace virtcom::cli {

std::expected<proto::modbus::ServerConfig, std::string> modbusServerConfig(const std::string& listen,
                                                                          const std::string& allow) {
  namespace mb = proto::modbus;
  auto endpoint = mb::parseEndpoint(listen);
  if (!endpoint) return std::unexpected("--modbus: " + endpoint.error());
  mb::ServerConfig config;
  config.listen = *endpoint;
  if (!allow.empty()) {
    auto peers = mb::parseAllowList(allow);
    if (!peers) return std::unexpected("--modbus-allow: " + peers.error());
    config.allowedPeers = *peers;
  }
  return config;
}

std::unique_ptr<proto::modbus::ClientBridge> startClientBridge(const cell::ModbusClientSettings& s, const std::string& role) {
  proto::modbus::ClientConfig config;
  config.peer = s.peer;
  config.unit = s.unit;
  config.pollNs = s.pollNs;
  config.timeoutNs = s.timeoutNs;
  config.faultOnLoss = s.faultOnLoss;
  config.map = s.map;
  config.report = [](const std::string& line) { std::cerr << line << "\n"; };
  std::cerr << "modbus: the PLC at " << s.address << " " << role << " (polled every " << s.pollNs / 1e6 << " ms)\n";
  return std::make_unique<proto::modbus::ClientBridge>(std::move(config));
}

}  // namespace virtcom::cli
