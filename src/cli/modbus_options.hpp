#pragma once
// The Modbus server settings that `exec` and `serve` share (docs/modbus.md): one place that
// checks --modbus and --modbus-allow, so both commands accept and refuse the same values.
#include <expected>
#include <string>

#include "proto/modbus/server.hpp"

namespace virtcom::cli {

// The server configuration for `--modbus LISTEN --modbus-allow ALLOW` (ALLOW empty: any peer).
// The error text names the option at fault.
std::expected<proto::modbus::ServerConfig, std::string> modbusServerConfig(const std::string& listen,
                                                                          const std::string& allow);

}  // namespace virtcom::cli
