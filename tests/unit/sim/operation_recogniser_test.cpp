// The operation recogniser of `virtcom monitor`: a simulated gearbox run's signal changes,
// replayed onto a second copy of the cell whose devices do not step, give back the run's own
// activities (device, operation, start, end, error); replayed slower, every operation deviates
// from the model and raises an alert.
#include <gtest/gtest.h>

#include "sim_rig.hpp"

namespace virtcom::sim::test {
namespace {

// The cell of `simulated` loaded again, its devices prepared (labels interned) but never stepped.
struct Watcher {
  CellRun run;
  explicit Watcher(const std::string& path) {
    EXPECT_TRUE(run.load(path)) << run.problems();
    for (auto& d : run.cell->devices) d->prepare(run.cell->world, run.cell->trace);
  }
  Trace& trace() { return run.cell->trace; }
};

// Feeds `simulated`'s changes onto `bus`, observing at each time that changed something, with
// times multiplied by `slowdown`.
void replay(const Trace& simulated, TagBus& bus, OperationRecogniser& recogniser, int64_t slowdown = 1) {
  for (TagId id = 0; id < bus.size(); ++id) bus.setRaw(id, simulated.signals[id].initial);
  recogniser.observe(bus, 0);
  const auto& changes = simulated.changes;
  for (size_t i = 0; i < changes.size();) {
    const int64_t t = changes[i].timeNs;
    for (; i < changes.size() && changes[i].timeNs == t; ++i)
      if (changes[i].tag < bus.size()) bus.setRaw(changes[i].tag, changes[i].raw);
    recogniser.observe(bus, t * slowdown);
  }
}

TEST(OperationRecogniser, ReplayingASimulatedRunGivesBackItsActivities) {
  auto simulated = runGearbox(3);
  ASSERT_TRUE(simulated);
  ASSERT_GT(simulated->trace().activities.size(), 20u);
  Watcher watcher(gearboxCellPath());
  OperationRecogniser recogniser(watcher.run.cell->devices, watcher.trace(), nullptr, 0.2);
  replay(simulated->trace(), watcher.run.cell->bus, recogniser);
  EXPECT_EQ(activitiesText(watcher.trace()), activitiesText(simulated->trace()));  // energy aside: not shown
  EXPECT_TRUE(watcher.trace().faults.empty());
}

TEST(OperationRecogniser, OperationsAsTheModelPredictsRaiseNoAlert) {
  auto simulated = runGearbox(3);
  ASSERT_TRUE(simulated);
  Watcher watcher(gearboxCellPath());
  OperationRecogniser recogniser(watcher.run.cell->devices, watcher.trace(), &simulated->trace(), 0.01);
  replay(simulated->trace(), watcher.run.cell->bus, recogniser);
  EXPECT_TRUE(watcher.trace().faults.empty());
  ASSERT_FALSE(recogniser.stats().empty());
  for (const OperationStats& s : recogniser.stats()) EXPECT_EQ(s.alerts, 0u) << watcher.trace().labels[s.label];
}

TEST(OperationRecogniser, APlantSlowerThanTheModelRaisesAlerts) {
  auto simulated = runGearbox(3);
  ASSERT_TRUE(simulated);
  Watcher watcher(gearboxCellPath());
  OperationRecogniser recogniser(watcher.run.cell->devices, watcher.trace(), &simulated->trace(), 0.5);
  replay(simulated->trace(), watcher.run.cell->bus, recogniser, 2);
  // An operation the model always does in one time T > 0 now takes 2 T every time: +100 %.
  size_t alerts = 0, fixed = 0;
  for (const OperationStats& s : recogniser.stats()) {
    alerts += s.alerts;
    if (s.expected.minNs != s.expected.maxNs || s.expected.minNs <= 0) continue;
    ++fixed;
    EXPECT_EQ(s.alerts, s.count) << watcher.trace().labels[s.label];
    EXPECT_DOUBLE_EQ(s.worstDeviation, 1.0) << watcher.trace().labels[s.label];
  }
  ASSERT_GT(fixed, 0u);
  ASSERT_EQ(watcher.trace().faults.size(), alerts);
  const FaultRecord& first = watcher.trace().faults.front();
  EXPECT_NE(first.message.find(" took "), std::string::npos) << first.message;
  EXPECT_NE(first.message.find(", the model "), std::string::npos) << first.message;
}

TEST(OperationRecogniser, JoiningWhileADoneIsHeldRecordsNothingUntilTheNextCommand) {
  Watcher watcher(gearboxCellPath());
  TagBus& bus = watcher.run.cell->bus;
  OperationRecogniser recogniser(watcher.run.cell->devices, watcher.trace(), nullptr, 0.2);
  const TagId execute = bus.find("Press.execute"), done = bus.find("Press.done");
  bus.setBool(execute, true);
  bus.setBool(done, true);
  recogniser.observe(bus, 0);  // the end of a command the monitor never saw start
  bus.setBool(execute, false);
  bus.setBool(done, false);
  recogniser.observe(bus, 10 * kMs);
  EXPECT_TRUE(watcher.trace().activities.empty());
  bus.setBool(execute, true);
  recogniser.observe(bus, 20 * kMs);
  bus.setBool(done, true);
  recogniser.observe(bus, 50 * kMs);
  ASSERT_EQ(watcher.trace().activities.size(), 1u);
  EXPECT_EQ(watcher.trace().activities[0].startNs, 20 * kMs);
  EXPECT_EQ(watcher.trace().activities[0].endNs, 50 * kMs);
}

TEST(OperationRecogniser, AnOperationRunningWhenJoinedIsRecordedButNotCompared) {
  auto simulated = runGearbox(3);
  ASSERT_TRUE(simulated);
  Watcher watcher(gearboxCellPath());
  TagBus& bus = watcher.run.cell->bus;
  OperationRecogniser recogniser(watcher.run.cell->devices, watcher.trace(), &simulated->trace(), 0.01);
  bus.setBool(bus.find("Press.execute"), true);
  bus.setBool(bus.find("Press.busy"), true);
  recogniser.observe(bus, 0);
  bus.setBool(bus.find("Press.busy"), false);
  bus.setBool(bus.find("Press.done"), true);
  recogniser.observe(bus, 10 * kMs);  // far shorter than the model's: its real start is unknown
  ASSERT_EQ(watcher.trace().activities.size(), 1u);
  EXPECT_EQ(watcher.trace().activities[0].endNs, 10 * kMs);
  EXPECT_TRUE(recogniser.stats().empty());
  EXPECT_TRUE(watcher.trace().faults.empty());
}

}  // namespace
}  // namespace virtcom::sim::test
