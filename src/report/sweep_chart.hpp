#pragma once
// The page of a parameter sweep (`virtcom sweep --html`, docs/optimise.md "Sweeps"): each KPI
// over the parameters as self-contained SVG (no script, no CDN) and the table of points. Two
// parameters make a heat map per KPI; otherwise one chart per parameter, the KPI over its values
// with a line per setting of the others. Knows nothing of the optimiser: a table of text values
// and KPIs in, HTML out. Deterministic; allocates.
#include <cstddef>
#include <string>
#include <vector>

namespace virtcom::report {

struct SweepTable {
  std::string title;                    // the sweep file
  std::vector<std::string> parameters;  // names, in the sweep's order
  struct Row {
    size_t point = 0;
    std::vector<std::string> values;    // one per parameter, as written (with units)
    bool feasible = false;
    double cycleS = 0, energyJ = 0;     // feasible only
    std::string result;                 // "ok" or why the point failed
  };
  std::vector<Row> rows;                // by point
};

std::string sweepHtml(const SweepTable& table);

}  // namespace virtcom::report
