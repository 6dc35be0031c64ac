// libFuzzer target for scenario files, as `virtcom test` runs them: each case (the file, or each
// of its first kRows parameter rows) through scenario::runCase: `${name}` substitution, the
// cell the scenario names loaded, the scenario bound to it (set, faults, steps, expect, xfail),
// then run with its stimuli and checker for at most kCycles PLC cycles of virtual time, whatever
// the scenario's time_limit says. The input is examples/gearbox-cell/tests/fuzz_scenario.yaml of
// the scratch tree (fuzz_scratch.hpp), beside the gearbox example's scenarios, so the seeds name
// the copy's cells as the examples do. Inputs naming a file outside the tree, as written or after
// substitution, are skipped. Finds crashes, leaks and UB in the reader, the expression parser,
// the binding, the stimuli and the checker; a case in error always says why.
#include <algorithm>
#include <cstdint>

#include "fuzz_scratch.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario_file.hpp"

namespace {

constexpr size_t kRows = 3;
constexpr int64_t kCycles = 200;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace scenario = virtcom::scenario;
  const virtcom::fuzz::Scratch& scratch = virtcom::fuzz::Scratch::get();
  const std::string path = scratch.write(virtcom::fuzz::kScenarioInput, data, size);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  scenario::ScenarioFile file;
  const bool read = scenario::readScenarioFile(path, sources, diags, file);
  if (read && !scratch.namesOnlyInside(file.root, dir)) return -1;
  const size_t rows = std::min(file.rows.size(), kRows);
  for (size_t row = 0; row < rows; ++row)
    if (!scratch.namesOnlyInside(scenario::substituteParameters(file.root, file.rows[row], diags), dir)) return -1;

  scenario::CaseOptions options;
  options.hooks.beforeRun = [](virtcom::cell::Cell& cell, const virtcom::SourceManager&, virtcom::sim::SimOptions& o,
                               std::string&) -> std::shared_ptr<void> {
    o.timeLimitNs = kCycles * cell.run.plcCycleNs;
    return nullptr;
  };
  for (size_t row = 0; row < std::max<size_t>(rows, 1); ++row) {
    scenario::CaseSpec spec;
    spec.file = path;
    spec.row = rows == 0 ? SIZE_MAX : row;
    const scenario::CaseResult result = scenario::runCase(spec, options);
    if (result.verdict == scenario::Verdict::Error && result.messages.empty()) __builtin_trap();  // an error always says why
  }
  return 0;
}
