#pragma once
// The external writes of a run in its HTML report (docs/report.md, docs/security.md): the writes
// clients made into the soft PLC over ADS, Modbus, OPC UA and the HMI, as a table.
#include <string>

#include "core/trace.hpp"

namespace virtcom::report {

// The panel headed by the count per protocol (externalWritesText), then a row per kept record
// (Trace::writeRecords: virtual time, wall time, protocol, peer, variable, old -> new), a note of
// how many more the run saw than it kept, or a note that it saw none. Empty when the run's
// writes were not audited. Names and values escaped. Deterministic; allocates.
std::string externalWritesHtml(const Trace& trace);

}  // namespace virtcom::report
