#pragma once
// A sweep's rows as a SQLite database (`virtcom sweep --sqlite`, docs/optimise.md "Sweeps"),
// written through the historian's SQLite handles: table `points` (one row per point: `point`,
// one TEXT column per parameter named as in the sweep file, `cycle_s`, `energy_J`, `result`),
// table `sweep` (what was swept, the same in every slice of it) and table `slices` (which
// slices the file holds). Slices' files merge into the database a single run writes.
#include <string>
#include <vector>

#include "optimize/sweep.hpp"
#include "report/sweep_chart.hpp"

namespace virtcom::optimize {

struct SweepSlice {
  size_t index = 1, count = 1;  // slice I of N, 1-based
  size_t points = 0;            // every point of the sweep, in all slices
};

// Writes `rows` (slice `slice` of the sweep) to a new database at `path`, replacing a file
// there. Returns "" or what went wrong.
std::string writeSweepDb(const std::string& path, const SweepSpec& spec, const SweepSlice& slice, const std::vector<SweepRow>& rows);

// Joins slices' databases into a new one at `out`: their `sweep` tables must agree, a point in
// two of them is an error. Returns "" or what went wrong, naming the file.
std::string mergeSweepDbs(const std::string& out, const std::vector<std::string>& inputs);

// Whether `path` starts as a SQLite database does (the merge tells databases from CSV by this).
bool isSqliteFile(const std::string& path);

// The table a sweep's page is drawn from: of rows just run, or read back from a database.
report::SweepTable sweepTable(const SweepSpec& spec, const std::vector<SweepRow>& rows);
std::string readSweepDb(const std::string& path, report::SweepTable& out);

}  // namespace virtcom::optimize
