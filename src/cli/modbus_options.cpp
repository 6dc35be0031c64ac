#include "cli/modbus_options.hpp"

#include <iostream>

namespace virtcom::cli {

std::expected<proto::modbus::ServerConfig, std::string> modbusServerConfig(const std::string& listen, const std::string& allow,
                                                                          const PeerFlags& peers) {
  namespace mb = proto::modbus;
  auto endpoint = mb::parseEndpoint(listen);
  if (!endpoint) return std::unexpected("--modbus: " + endpoint.error());
  mb::ServerConfig config;
  config.listen = *endpoint;
  auto policy = peerPolicy(*endpoint, peers, "modbus", "--modbus", "--modbus-allow", allow);
  if (!policy) return std::unexpected(policy.error());
  config.peers = std::move(*policy);
  return config;
}

void addModbusServeOptions(CLI::App* cmd, std::string& allow, bool& readOnly) {
  cmd->add_option("--modbus-allow", allow,
                  "comma-separated IPv4 peers (ADDRESS or ADDRESS/BITS) allowed to connect to --modbus (needed to bind beyond "
                  "loopback; see docs/security.md)");
  cmd->add_flag("--modbus-readonly", readOnly, "refuse every Modbus write (exception 01: the write functions are not offered)");
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
