// Sweeps: their points (grid and seeded random), one row per point evaluated by the optimiser's
// core on an edited copy of the cell, and the mistakes a sweep file can make.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "optimize/sweep.hpp"

namespace virtcom::optimize {
namespace {

const std::string kSweep = VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/sweep.yaml";

TEST(Sweep, GridVisitsEveryCombinationLastParameterFastest) {
  SweepSpec s;
  s.parameters = {{"a", {"1", "2"}, {}}, {"b", {"x", "y", "z"}, {}}};
  auto points = sweepPoints(s);
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[0], (std::vector<size_t>{0, 0}));
  EXPECT_EQ(points[1], (std::vector<size_t>{0, 1}));
  EXPECT_EQ(points[5], (std::vector<size_t>{1, 2}));
}

TEST(Sweep, RandomSamplesDependOnlyOnTheSeed) {
  SweepSpec s;
  s.parameters = {{"a", {"1", "2", "3"}, {}}, {"b", {"x", "y"}, {}}};
  s.random = true;
  s.samples = 20;
  s.seed = 4;
  auto a = sweepPoints(s);
  EXPECT_EQ(a, sweepPoints(s));
  ASSERT_EQ(a.size(), 20u);
  for (const auto& p : a) EXPECT_TRUE(p[0] < 3 && p[1] < 2);
  s.seed = 5;
  EXPECT_NE(a, sweepPoints(s));
}

TEST(Sweep, EachPointRunsTheCellWithItsValues) {
  SourceManager sources;
  Diagnostics diags;
  auto spec = readSweep(kSweep, sources, diags);
  ASSERT_TRUE(spec) << diags.render(sources);
  auto sweeper = Sweeper::create(*spec, sources, diags);
  ASSERT_TRUE(sweeper) << diags.render(sources);
  const auto points = sweepPoints(*spec);
  ASSERT_EQ(points.size(), 6u);
  SweepRow asWritten = sweeper->evaluate(4, points[4]);  // sequence 3, 1150 mm/s: the cell as it is
  EXPECT_EQ(asWritten.values, (std::vector<std::string>{"3", "1150 mm/s"}));
  ASSERT_TRUE(asWritten.eval.feasible) << asWritten.eval.reason;
  EXPECT_EQ(asWritten.eval.cycleNs, 70'950'000'000);
  SweepRow faster = sweeper->evaluate(5, points[5]);
  SweepRow slower = sweeper->evaluate(3, points[3]);
  EXPECT_LT(faster.eval.cycleNs, asWritten.eval.cycleNs);
  EXPECT_GT(slower.eval.cycleNs, asWritten.eval.cycleNs);
  EXPECT_EQ(sweeper->evaluate(1, points[1]).eval.cycleNs, 74'820'000'000) << "sequence 2 at 1150 mm/s";
  const std::string csv = sweepCsv(*spec, {asWritten});
  EXPECT_EQ(csv, "point,MAIN.sequence,Robot1.max_speed,cycle_s,energy_J,result\n4,3,1150 mm/s,70.950,21977.1,ok\n");
}

TEST(Sweep, UnknownParameterAndRefusedValueAreReportedAtTheSweepFile) {
  const std::string path = (std::filesystem::temp_directory_path() / ("sweep_" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(path) << "cell: " VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/cell.yaml\n"
                         "parameters:\n"
                         "  MAIN.nothing: [1]\n"
                         "  Robot1.max_speed: [fast]\n";
  SourceManager sources;
  Diagnostics diags;
  auto spec = readSweep(path, sources, diags);
  ASSERT_TRUE(spec) << diags.render(sources);
  EXPECT_FALSE(Sweeper::create(*spec, sources, diags));
  const std::string text = diags.render(sources);
  EXPECT_NE(text.find(":3:3: error[C070]: 'MAIN.nothing' names neither a device parameter of the cell (DEVICE.key) nor a PLC variable"),
            std::string::npos) << text;
  std::ofstream(path) << "cell: " VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/cell.yaml\n"
                         "parameters:\n"
                         "  Robot1.max_speed: [fast]\n";
  Diagnostics again;
  auto refused = readSweep(path, sources, again);
  ASSERT_TRUE(refused);
  EXPECT_FALSE(Sweeper::create(*refused, sources, again));
  EXPECT_NE(again.render(sources).find(":3:3: error[C010]"), std::string::npos) << again.render(sources);
  std::filesystem::remove(path);
}

// The diagnostics of reading the sweep file `text`, which must be refused.
std::string refusal(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / (name + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(path) << text;
  SourceManager sources;
  Diagnostics diags;
  EXPECT_FALSE(readSweep(path, sources, diags));
  std::filesystem::remove(path);
  return diags.render(sources);
}

// Found writing the fuzz target fuzz_sweep_file: `samples: -1` was cast to 2^64 - 1 points.
TEST(Sweep, NegativeSamplesAreRefused) {
  const std::string text = refusal("sweep_samples_",
                                   "cell: cell.yaml\n"
                                   "sampling: random\n"
                                   "samples: -1\n"
                                   "parameters:\n"
                                   "  MAIN.sequence: [1, 2]\n");
  EXPECT_NE(text.find(":3:10: error[C070]: 'samples' is -1, expected a positive number of points"), std::string::npos) << text;
}

// Found by fuzz_sweep_file: a time limit of 2e53 s was converted to int64 nanoseconds (undefined).
TEST(Sweep, AnOutOfRangeTimeLimitIsRefused) {
  const std::string text = refusal("sweep_limit_",
                                   "cell: cell.yaml\n"
                                   "time_limit: 222222222222222222222222222222222222222222222222222120 s\n"
                                   "parameters:\n"
                                   "  MAIN.sequence: [1, 2]\n");
  EXPECT_NE(text.find(":2:13: error[C070]: 'time_limit' is out of range, expected at most 9e9 s"), std::string::npos) << text;
}

}  // namespace
}  // namespace virtcom::optimize
