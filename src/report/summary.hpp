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

// "3 of 1000 ticks started late (at most 12.345 ms)" or "none of 1000 ticks started late": a
// paced run's timing (TimeSteps::lateTicks), in the summary table and `exec --speed`'s end line.
std::string lateTicksText(uint64_t late, uint64_t ticks, int64_t maxLateNs);

}  // namespace virtcom::report
