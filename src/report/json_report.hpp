#pragma once
// Machine-readable run report. The schema is documented field by field in docs/report.md.
#include <string>

#include "core/trace.hpp"
#include "report/kpis.hpp"
#include "report/production.hpp"

namespace virtcom::report {

// Bumped whenever a field changes meaning or disappears (adding fields keeps the version).
inline constexpr int kJsonSchemaVersion = 1;

// The KPIs plus every activity, collision and fault as a JSON document (2-space indented, keys
// in a fixed order, times in seconds, energies in joules, ends with '\n'). Invalid UTF-8 in
// names is replaced by U+FFFD. Deterministic; `kpis` must come from computeKpis(trace).
// With `production` (virtcom monitor), a "production" member as well: shifts, days and stations.
std::string jsonReport(const Trace& trace, const Kpis& kpis, const ProductionReport* production = nullptr);

}  // namespace virtcom::report
