// libFuzzer target for sweep files (`virtcom sweep SWEEP.yaml`, docs/optimise.md "Sweeps"):
// readSweep, then the sweep's points (grid or seeded random) when there are at most kMaxPoints
// of them (a sweep of millions of points is a legitimate request that only costs memory), and
// the CSV of one empty row per point. The sweep's `cell:` is only resolved, never read here (the
// cell file has its own target, fuzz_cell). Finds crashes, leaks and UB in the reader and the
// point generator; a rejected sweep always says why.
#include <cstdint>

#include "fuzz_scratch.hpp"
#include "optimize/sweep.hpp"

namespace {

constexpr size_t kMaxPoints = 4096;

// The number of points sweepPoints() makes, saturated at kMaxPoints + 1.
size_t pointCount(const virtcom::optimize::SweepSpec& spec) {
  if (spec.random) return std::min(spec.samples, kMaxPoints + 1);
  size_t n = 1;
  for (const auto& p : spec.parameters) n = std::min(n * p.values.size(), kMaxPoints + 1);
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace optimize = virtcom::optimize;
  const auto spec = virtcom::fuzz::readInput(virtcom::fuzz::kSweepInput, data, size, optimize::readSweep);
  if (!spec) return 0;
  if (pointCount(*spec) > kMaxPoints) return 0;
  const auto points = optimize::sweepPoints(*spec);
  std::vector<optimize::SweepRow> rows;
  for (size_t i = 0; i < points.size(); ++i) {
    optimize::SweepRow row;
    row.point = i;
    for (size_t k = 0; k < points[i].size(); ++k) row.values.push_back(spec->parameters[k].values.at(points[i][k]));
    rows.push_back(std::move(row));
  }
  optimize::sweepCsv(*spec, rows);
  return 0;
}
