#pragma once
// Parameter sweeps (`virtcom sweep`, docs/optimise.md "Sweeps"): device parameters of the cell
// file (`Robot1.max_speed`) and PLC variables (`MAIN.sequence`) over lists of values, on a grid
// (every combination) or sampled at random (seeded); one cycle per point, evaluated by the same
// core as the optimiser (runInstance: a fresh cell from one compiled template), one KPI row each.
// Points are numbered, so slices of a sweep (--shard I/N) run apart and merge into the same table.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "optimize/evaluator.hpp"

namespace virtcom::optimize {

struct SweepParameter {
  std::string name;                 // "Robot1.max_speed" or "MAIN.sequence"
  std::vector<std::string> values;  // as written (with units for device parameters)
  SourceLocation loc;
};

struct SweepSpec {
  std::filesystem::path file;
  std::string cellFile;
  std::vector<std::pair<std::string, std::string>> presets;  // `set:` fixed PLC values
  std::vector<SweepParameter> parameters;
  bool random = false;              // `sampling: random`
  size_t samples = 0;               // random: how many points
  uint64_t seed = 1;
  int64_t timeLimitNs = 0;          // 0: the cell's
};

std::optional<SweepSpec> readSweep(const std::string& path, SourceManager& sources, Diagnostics& diags);

// The points, each an index into every parameter's values: a grid (the last parameter varies
// fastest) or `samples` seeded random draws.
std::vector<std::vector<size_t>> sweepPoints(const SweepSpec& spec);

struct SweepRow {
  size_t point = 0;  // 0-based number in sweepPoints()
  std::vector<std::string> values;
  Evaluation eval;
};

class Sweeper {
 public:
  // Reads the cell and compiles its program once; checks that every parameter names a device
  // parameter of the cell file or a PLC variable, and every value (C070 at the sweep file). Null on errors.
  static std::unique_ptr<Sweeper> create(const SweepSpec& spec, SourceManager& sources, Diagnostics& diags);
  // One point's row. Thread-safe.
  SweepRow evaluate(size_t point, const std::vector<size_t>& at) const;
  // A point's values as written in the sweep file.
  std::vector<std::string> values(const std::vector<size_t>& at) const;

 private:
  explicit Sweeper(const SweepSpec& spec) : spec_(spec) {}
  ConfigNode editedRoot(const std::vector<size_t>& at) const;
  const SweepSpec& spec_;
  std::unique_ptr<cell::CellTemplate> template_;
  std::vector<int> deviceIndex_;  // per parameter: its device's place in the cell's list, -1: a PLC variable
  std::vector<std::optional<bc::VarRef>> variables_;
  std::vector<std::pair<bc::VarRef, std::string>> presets_;
};

// The rows as CSV: point, the parameters, cycle_s, energy_J, result.
std::string sweepCsv(const SweepSpec& spec, const std::vector<SweepRow>& rows);

}  // namespace virtcom::optimize
