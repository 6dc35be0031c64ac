#pragma once
// Reading the cell file's `hmi:` section (loader internals; the settings: hmi_settings.hpp).
#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// `hmi:` (null: absent) into cell.hmi. Needs the devices (names are resolved against them).
// Reports every mistake at its position: unknown keys C011, values C010, unknown devices C040,
// inconsistent drawing (half a coordinate pair, a robot base on another kind, a bad colour) C041.
void readHmiSection(Cell& cell, const ConfigNode* node, Diagnostics& diags);

}  // namespace virtcom::cell
