#pragma once
// The OPC UA client bridge to an external PLC as `run` and `test` start it (`plc: opcua:`, the
// PLC is the controller): one place that maps the wired variables to node ids, connects,
// checks every node and reports problems like the loader's.
#include <memory>
#include <string>

#include "cell/cell.hpp"
#include "core/source.hpp"
#include "proto/opcua/client_bridge.hpp"

namespace virtcom::cli {

// The node of a wired variable (docs/opcua.md "The client bridge"): as `nodes:` names it (a node
// id or a browse path), the variable itself when written as a node id ("ns=2;i=17"), else
// node_prefix + variable.
std::string opcuaNodeOf(const cell::OpcuaClientSettings& s, const std::string& variable);

// Connects to the PLC of cell.plcOpcua and checks its wires. Problems are rendered on stderr
// at the cell file's entries, as the loader's are (a node `nodes:` names: at that entry); null then. On success prints
// "opcua: <the server> <role> (N signals, subscribed, published every POLL)", or "a Read every
// POLL" where the server refuses subscriptions.
std::unique_ptr<proto::opcua::ClientBridge> startOpcuaBridge(cell::Cell& cell, const SourceManager& sources, const std::string& role);

}  // namespace virtcom::cli
