#pragma once
// The cell file's Modbus parts (loader internals): the top-level `modbus:` section (what
// `virtcom serve` serves) and `plc: modbus:` (the client bridge to an external PLC).
#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// `modbus:` (null: absent, the automatic map) into cell.modbus; rejects unknown keys.
void readModbusSection(Cell& cell, const ConfigNode* node, Diagnostics& diags);
// `plc: modbus:` into cell.plcModbus; reports every problem at its position.
void readModbusClient(Cell& cell, const ConfigNode& node, Diagnostics& diags);

}  // namespace virtcom::cell
