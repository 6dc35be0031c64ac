#pragma once
// What the ADS and OPC UA bridge starters (ads_client.cpp, opcua_client.cpp) check alike once
// the PLC has answered: wiring by prefix (`wiring: MAIN.Robot1`) needs, for each such device,
// at least one port whose variable the PLC has.
#include <functional>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "core/diagnostics.hpp"

namespace virtcom::cli {

// One C030 error per device wired by prefix none of whose variables was `found` (per wire), at
// its wiring entry; `message(first wire, device, prefix)` words it for the protocol.
void reportUnmatchedPrefixes(const std::vector<cell::ExternalWire>& wires, const std::vector<bool>& found, Diagnostics& diags,
                             const std::function<std::string(const cell::ExternalWire&, const std::string&, const std::string&)>& message);

}  // namespace virtcom::cli
