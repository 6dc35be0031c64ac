#pragma once
// The cell file's `plc: opcua:` (loader internals): the OPC UA client bridge to an external PLC.
#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// The keys of `plc: opcua:` into `s` (its wires are the loader's business); reports every
// problem at its position.
void readOpcuaClient(OpcuaClientSettings& s, const ConfigNode& node, Diagnostics& diags);

}  // namespace virtcom::cell
