#include "cli/modbus_options.hpp"

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

}  // namespace virtcom::cli
