#pragma once
// The plain-text run summary the CLI prints after a simulation.
#include <string>

#include "core/trace.hpp"
#include "report/kpis.hpp"

namespace virtcom::report {

// Renders the per-device table (device, type, busy s, idle s, utilisation %, energy J,
// operations, errors), then cycle time, total energy, collisions (time, zone, devices and what
// each was doing), faults and how the run ended. ASCII column layout that fits 100 columns
// (long names are cut with '~'); every line ends in '\n'. Deterministic; `kpis` must come from
// computeKpis(trace).
std::string summaryTable(const Trace& trace, const Kpis& kpis);

// The last lines of summaryTable(): the faults (time, source, message) and how the run ended.
// What `--quiet` still prints, so a failed run never ends without saying why.
std::string runOutcome(const Trace& trace, const Kpis& kpis);

}  // namespace virtcom::report
