#pragma once
// A run report as ONE self-contained HTML file: inline CSS and SVG, no external resources and no
// JavaScript, so it opens offline and can be mailed or attached to a commissioning record.
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "report/diagram_tables.hpp"
#include "report/kpis.hpp"

namespace virtcom::report {

struct HtmlOptions {
  std::string title;                  // cell name for the heading; empty -> "virtcom run"
  std::string subtitle;               // optional second line (e.g. the scenario file)
  std::vector<std::string> signals;   // signal timeline lanes, in this order (exact names)
  int chartWidthPx = 1200;            // width of the Gantt and signal charts, clamped to 640..4000
  // Charts show only the measured cycle (when the run has cycle markers) instead of the whole
  // run: the one-cycle view of seed Figure 11, useful for long runs of many cycles.
  bool cycleOnly = false;
  // The PLC program's activity diagrams: their LU and rule tables with the rules' firings.
  std::vector<DiagramTablesSection> diagrams;
};

// Renders the page: heading, KPI cards (cycle time, energy, operations, errors, collisions,
// faults, run end), the Gantt chart (one lane per device, grouped robots / press / axes / other,
// bars coloured per operation label with a legend, errors outlined red, still-running bars
// dashed, collision and fault markers, the measured cycle shaded, a time axis in seconds), the
// device table with utilisation bars, energy per robot, the signal timeline for
// `options.signals` (BOOL as digital waveforms, numbers as step plots), the collision and
// fault lists and the tables of `options.diagrams` (diagram_tables.hpp). All names are escaped.
// Output size is bounded by the chart width, not the run length: bars narrower than 2 px are
// merged and signal plots keep at most 4 points per pixel column. Deterministic; `kpis` must come from computeKpis(trace).
std::string htmlReport(const Trace& trace, const Kpis& kpis, const HtmlOptions& options);

}  // namespace virtcom::report
