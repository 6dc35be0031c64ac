// Signal changes stream to sinks as the run goes, and a run keeps in memory only the signals it
// is told to keep: the files are the same bytes as from a run that kept everything, and the
// memory of a long run does not grow with its length.
#include <gtest/gtest.h>

#include <sstream>

#include "sim_rig.hpp"

namespace virtcom::sim::test {
namespace {

// Counts what reaches it and checks the sink contract (begin first, changes in time order, end last).
struct CountingSink final : TraceSink {
  int begins = 0, ends = 0;
  size_t changes = 0, ticks = 0;
  size_t activitiesSeenAtTicks = 0;  // the trace's activity count at the last tick
  int64_t lastNs = 0;
  bool ordered = true;
  void begin(const Trace&) override { ++begins; }
  void change(const SignalChange& c) override {
    ordered = ordered && begins == 1 && ends == 0 && c.timeNs >= lastNs;
    lastNs = c.timeNs;
    ++changes;
  }
  void tick(const Trace& trace, int64_t nowNs) override {
    ordered = ordered && begins == 1 && ends == 0 && nowNs >= lastNs;  // after this tick's changes
    lastNs = nowNs;
    activitiesSeenAtTicks = trace.activities.size();
    ++ticks;
  }
  void end(const Trace&) override { ++ends; }
};

std::unique_ptr<CellRun> loadGearbox() {
  auto run = std::make_unique<CellRun>();
  if (!run->load(gearboxCellPath())) ADD_FAILURE() << run->problems();
  return run;
}

TEST(StreamingTrace, StreamedFilesEqualTheFilesOfARunThatKeptEveryChange) {
  auto full = runGearbox(3);
  ASSERT_TRUE(full);
  std::string expectedVcd = report::vcdReport(full->trace());
  std::string expectedCsv = full->csv();

  auto streamed = loadGearbox();
  std::ostringstream vcd, csv;
  report::VcdWriter vcdWriter(vcd);
  report::CsvWriter csvWriter(csv);
  CountingSink counter;
  SimOptions options;
  options.preset = presets({{"MAIN.sequence", "3"}});
  options.keepAllChanges = false;
  options.keptSignals = {"Robot1.busy"};
  options.traceSinks = {&vcdWriter, &csvWriter, &counter};
  EXPECT_EQ(streamed->run(std::move(options)), RunEnd::Completed);

  EXPECT_EQ(vcd.str(), expectedVcd);
  EXPECT_EQ(csv.str(), expectedCsv);
  EXPECT_EQ(counter.begins, 1);
  EXPECT_EQ(counter.ends, 1);
  EXPECT_TRUE(counter.ordered);
  EXPECT_EQ(counter.changes, full->trace().changes.size());
  // Every tick reached the sink, and by the last one it had seen every activity of the run.
  EXPECT_EQ(counter.ticks, streamed->simulation->ticks());
  EXPECT_EQ(counter.activitiesSeenAtTicks, full->trace().activities.size());
  // Only the kept signal stays in memory, with exactly its changes of the full run.
  std::vector<SignalChange> expectedKept;
  for (const SignalChange& c : full->trace().changes)
    if (full->trace().signals[c.tag].name == "Robot1.busy") expectedKept.push_back(c);
  ASSERT_FALSE(expectedKept.empty());
  ASSERT_EQ(streamed->trace().changes.size(), expectedKept.size());
  for (size_t i = 0; i < expectedKept.size(); ++i) {
    EXPECT_EQ(streamed->trace().changes[i].timeNs, expectedKept[i].timeNs);
    EXPECT_EQ(streamed->trace().changes[i].raw, expectedKept[i].raw);
  }
  // The rest of the trace (activities, KPIs) is the same: the JSON report does not change.
  EXPECT_EQ(streamed->json(), full->json());
}

TEST(StreamingTrace, ARunThatKeepsNoSignalHoldsNoChangesHoweverLongItRuns) {
  auto run = loadGearbox();
  CountingSink counter;
  SimOptions options;
  options.preset = presets({{"MAIN.sequence", "3"}});
  options.keepAllChanges = false;
  options.traceSinks = {&counter};
  run->run(std::move(options));
  EXPECT_GT(counter.changes, 1000u);
  EXPECT_TRUE(run->trace().changes.empty());
  EXPECT_EQ(run->trace().changes.capacity(), 0u);  // not even reserved
}

}  // namespace
}  // namespace virtcom::sim::test
