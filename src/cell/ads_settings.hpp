#pragma once
// The cell file's `plc: ads:` (loader internals): the ADS client bridge to an external PLC.
#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// The keys of `plc: ads:` into `s` (its wires are the loader's business); reports every problem
// at its position.
void readAdsClient(AdsClientSettings& s, const ConfigNode& node, Diagnostics& diags);

}  // namespace virtcom::cell
