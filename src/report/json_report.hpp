#pragma once
// Machine-readable run report. The schema is documented field by field in docs/report.md.
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "report/diagram_tables.hpp"
#include "report/kpis.hpp"
#include "report/production.hpp"

namespace virtcom::report {

// Bumped whenever a field changes meaning or disappears (adding fields keeps the version).
inline constexpr int kJsonSchemaVersion = 1;

// The KPIs plus every activity, collision and fault as a JSON document (2-space indented, keys
// in a fixed order, times in seconds, energies in joules, ends with '\n'). Invalid UTF-8 in
// names is replaced by U+FFFD. Deterministic; `kpis` must come from computeKpis(trace).
// `diagrams` (the PLC program's activity diagrams with their rule firings) adds the key
// "diagrams" when not empty; `production` (virtcom monitor) a "production" member: shifts, days
// and stations.
std::string jsonReport(const Trace& trace, const Kpis& kpis, const std::vector<DiagramTablesSection>& diagrams = {},
                       const ProductionReport* production = nullptr);

}  // namespace virtcom::report
