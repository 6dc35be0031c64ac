#pragma once
// The Modbus settings that commands share (docs/modbus.md): the server options of `exec` and
// `serve` (one place that checks --modbus and --modbus-allow, so both accept and refuse the same
// values) and the client bridge that `run` (`plc: modbus:`) and `monitor --modbus` start.
#include <expected>
#include <memory>
#include <string>

#include "cell/cell.hpp"
#include "cli/peer_options.hpp"
#include "proto/modbus/client_bridge.hpp"
#include "proto/modbus/server.hpp"

namespace virtcom::cli {

// The server configuration for `--modbus LISTEN --modbus-allow ALLOW` with the command's peer
// flags (ALLOW empty: any peer, on loopback only). The error text names the option at fault.
std::expected<proto::modbus::ServerConfig, std::string> modbusServerConfig(const std::string& listen, const std::string& allow,
                                                                          const PeerFlags& peers);
// Adds --modbus-allow and --modbus-readonly (what `exec` and `serve` share besides --modbus).
void addModbusServeOptions(CLI::App* cmd, std::string& allow, bool& readOnly);

// The client bridge polling the PLC of `s`; prints "modbus: the PLC at ADDRESS <role> (polled
// every N ms)". It connects at its first poll.
std::unique_ptr<proto::modbus::ClientBridge> startClientBridge(const cell::ModbusClientSettings& s, const std::string& role);

}  // namespace virtcom::cli
