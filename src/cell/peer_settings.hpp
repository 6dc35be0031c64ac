#pragma once
// The keys both external-PLC sections of the cell file have (`plc: modbus:`, `plc: ads:`;
// loader internals): read by one function each, so both sections accept the same text and
// report the same mistakes in the same words, at the key's position.
#include <cstdint>
#include <string>

#include "core/config_node.hpp"
#include "core/endpoint.hpp"

namespace virtcom::cell {

// The required `address: HOST:PORT` of the PLC's server into `text` (as written) and
// `endpoint`. A malformed address or port 0 is reported with `example` ("127.0.0.1:502").
void readPeerAddress(ConfigReader& r, const ConfigNode& node, const char* example, std::string& text, Endpoint& endpoint);

// `key: DURATION` (default `defaultS` seconds) in ns; less than 1 ms is reported.
int64_t readLinkDurationNs(ConfigReader& r, const ConfigNode& node, const char* key, double defaultS);

// `on_loss: fault | hold` (default fault): true for fault (end the run when the link is lost).
bool readFaultOnLoss(ConfigReader& r, const ConfigNode& node);

}  // namespace virtcom::cell
