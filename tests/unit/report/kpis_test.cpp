#include <gtest/gtest.h>

#include "report/kpis.hpp"
#include "example_trace.hpp"

namespace virtcom::report {
namespace {

using testing::activity;
using testing::exampleCellTrace;
using testing::kS;

TEST(Kpis, CycleWindowFromMarkers) {
  Kpis k = computeKpis(exampleCellTrace());
  EXPECT_TRUE(k.cycleMeasured);
  EXPECT_EQ(k.windowStartNs, 2 * kS);
  EXPECT_EQ(k.windowEndNs, 73 * kS);
  EXPECT_EQ(k.cycleTimeNs, 71 * kS);
  EXPECT_EQ(k.runNs, 75 * kS);
  EXPECT_EQ(k.cyclesCompleted, 1u);
}

TEST(Kpis, BusyTimeIsTheUnionOfActivitiesClippedToTheWindow) {
  Kpis k = computeKpis(exampleCellTrace());
  ASSERT_EQ(k.devices.size(), 6u);
  int64_t busy[] = {46, 38, 19, 5, 4, 5};
  for (size_t d = 0; d < 6; ++d) {
    EXPECT_EQ(k.devices[d].device, d);
    EXPECT_EQ(k.devices[d].busyNs, busy[d] * kS) << "device " << d;
    EXPECT_EQ(k.devices[d].idleNs, (71 - busy[d]) * kS) << "device " << d;
    EXPECT_DOUBLE_EQ(k.devices[d].utilisationPct, 100.0 * static_cast<double>(busy[d]) / 71.0);
  }
}

TEST(Kpis, OperationsErrorsAndRunningActivities) {
  Kpis k = computeKpis(exampleCellTrace());
  uint32_t ops[] = {6, 5, 2, 2, 2, 1};
  for (size_t d = 0; d < 6; ++d) EXPECT_EQ(k.devices[d].operations, ops[d]) << "device " << d;
  EXPECT_EQ(k.operations, 18u);
  EXPECT_EQ(k.devices[1].errors, 1u);
  EXPECT_EQ(k.errors, 1u);
  EXPECT_EQ(k.devices[1].running, 1u);
  EXPECT_EQ(k.devices[0].running, 0u);
  EXPECT_DOUBLE_EQ(k.devices[0].activityEnergyJ, 300 + 650 + 1400 + 500 + 900 + 400);
}

TEST(Kpis, EnergyComesFromTheTotals) {
  Kpis k = computeKpis(exampleCellTrace());
  EXPECT_DOUBLE_EQ(k.devices[0].energyJ, 4871.2);
  EXPECT_DOUBLE_EQ(k.devices[1].energyJ, 12196.1);
  EXPECT_NEAR(k.totalEnergyJ, 22963.05, 1e-9);
}

TEST(Kpis, EventsAndEnd) {
  Kpis k = computeKpis(exampleCellTrace());
  EXPECT_EQ(k.collisions, 1u);
  EXPECT_EQ(k.faults, 1u);
  EXPECT_EQ(k.end, RunEnd::TimeLimit);
  EXPECT_EQ(k.endMessage, "time limit of 75 s reached");
}

TEST(Kpis, WithoutCycleMarkersTheWholeRunIsTheWindow) {
  Trace t;
  uint32_t d = t.addDevice("R", "robot");
  activity(t, d, "A", 1, 3, 5);
  activity(t, d, "B", 2, 4, 5);   // overlaps A: union 1..4
  activity(t, d, "C", 4, 4, 1);   // zero length: counts as an operation, adds no time
  activity(t, d, "D", 8, 10, 5);
  t.endNs = 10 * kS;
  Kpis k = computeKpis(t);
  EXPECT_FALSE(k.cycleMeasured);
  EXPECT_EQ(k.windowStartNs, 0);
  EXPECT_EQ(k.cycleTimeNs, 10 * kS);
  EXPECT_EQ(k.devices[0].busyNs, 5 * kS);
  EXPECT_EQ(k.devices[0].idleNs, 5 * kS);
  EXPECT_DOUBLE_EQ(k.devices[0].utilisationPct, 50.0);
  EXPECT_EQ(k.devices[0].operations, 4u);
}

TEST(Kpis, NestedActivitiesCountOnce) {
  Trace t;
  uint32_t d = t.addDevice("R", "robot");
  activity(t, d, "Outer", 0, 10, 0);
  activity(t, d, "Inner", 2, 3, 0);
  activity(t, d, "Tail", 9, 12, 0);
  t.endNs = 20 * kS;
  Kpis k = computeKpis(t);
  EXPECT_EQ(k.devices[0].busyNs, 12 * kS);
}

TEST(Kpis, ToleratesEmptyAndInconsistentTraces) {
  Trace empty;
  Kpis k = computeKpis(empty);
  EXPECT_EQ(k.cycleTimeNs, 0);
  EXPECT_TRUE(k.devices.empty());

  Trace t;
  t.devices.push_back({"NoTotals", "robot", ""});       // totals not filled
  t.activities.push_back({7, 0, 0, kS, 1.0, 0});        // unknown device: skipped
  t.activities.push_back({0, 99, 0, 2 * kS, 1.0, 0});   // unknown label: still counted
  t.endNs = 4 * kS;
  k = computeKpis(t);
  ASSERT_EQ(k.devices.size(), 1u);
  EXPECT_EQ(k.devices[0].energyJ, 0.0);
  EXPECT_EQ(k.devices[0].busyNs, 2 * kS);
  EXPECT_EQ(k.devices[0].utilisationPct, 50.0);
  EXPECT_EQ(k.operations, 1u);
}

}  // namespace
}  // namespace virtcom::report
