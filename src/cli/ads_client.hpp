#pragma once
// The ADS client bridge to an external PLC as `run` (`plc: ads:`, the PLC is the controller)
// and `monitor` (the real plant's PLC, only read) start it: one place that connects, checks
// every wired variable and reports problems like the loader's.
#include <memory>
#include <string>

#include "cell/cell.hpp"
#include "core/source.hpp"
#include "proto/ads/client_bridge.hpp"

namespace virtcom::cli {

// Connects to the PLC of cell.plcAds and resolves its wires (docs/ads.md "The client bridge").
// Problems are rendered on stderr at the cell file's entries, as the loader's are; null then.
// On success prints "ads: <the PLC> <role> (N signals by handle, every step)".
std::unique_ptr<proto::ads::ClientBridge> startAdsBridge(cell::Cell& cell, const SourceManager& sources, const std::string& role);

}  // namespace virtcom::cli
