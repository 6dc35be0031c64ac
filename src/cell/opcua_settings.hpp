#pragma once
// The cell file's `plc: opcua:`: the OPC UA client bridge to an external PLC (read by the loader;
// `virtcom monitor --opcua` takes an endpoint URL the same way).
#include <filesystem>
#include <expected>
#include <string>
#include <string_view>

#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// The keys of `plc: opcua:` into `s` (its wires are the loader's business); reports every
// problem at its position. `cellDir`: what a relative `pki:` folder is relative to.
void readOpcuaClient(OpcuaClientSettings& s, const ConfigNode& node, const std::filesystem::path& cellDir, Diagnostics& diags);

// The server of an endpoint URL, `opc.tcp://HOST:PORT[/PATH]`; the reason (with the expected
// form) if it is not one.
std::expected<Endpoint, std::string> opcuaServerOf(std::string_view url);

}  // namespace virtcom::cell
