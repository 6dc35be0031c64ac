#include <gtest/gtest.h>

#include <sstream>

#include "report/kpis.hpp"
#include "report/summary.hpp"
#include "example_trace.hpp"
#include "golden_file.hpp"

namespace virtcom::report {
namespace {

using testing::expectGolden;
using testing::kS;

TEST(SummaryTable, MatchesGolden) {
  Trace t = testing::exampleCellTrace();
  expectGolden("summary.txt", summaryTable(t, computeKpis(t)));
}

TEST(SummaryTable, FitsA100ColumnTerminal) {
  Trace t = testing::exampleCellTrace();
  t.devices[0].name = "VeryLongRobotNameThatGoesOnAndOnForeverAndEver";
  t.devices[0].type = "articulated-robot-6-axis";
  std::istringstream lines(summaryTable(t, computeKpis(t)));
  std::string line;
  bool sawCut = false;
  while (std::getline(lines, line)) {
    if (line.find("Run ended") == 0 || line.find("s  Robot2:") != std::string::npos) continue;  // free text
    EXPECT_LE(line.size(), 100u) << line;
    sawCut |= line.find("VeryLongRobotNameThatGo~") != std::string::npos;
  }
  EXPECT_TRUE(sawCut);
}

TEST(SummaryTable, RunWithoutCycleMarkersOrDevices) {
  Trace t;
  t.endNs = 3 * kS;
  t.end = RunEnd::Completed;
  std::string s = summaryTable(t, computeKpis(t));
  EXPECT_NE(s.find("Cycle time    3.000 s (whole run, no cycle markers)\n"), std::string::npos) << s;
  EXPECT_NE(s.find("Collisions    0\n"), std::string::npos);
  EXPECT_NE(s.find("Run ended     completed\n"), std::string::npos);
}

// Several cycles: min, mean and max and every cycle, so "Cycle time" (the last cycle) is not
// mistaken for the mean (issue 16). One cycle: no table.
TEST(SummaryTable, SeveralCyclesAreListed) {
  Trace t = testing::threeCycleTrace();
  const std::string out = summaryTable(t, computeKpis(t));
  EXPECT_NE(out.find("Cycle time    21.000 s (measured cycle 52.000 s .. 73.000 s, 3 cycles completed)\n"
                     "Cycles        min 21.000 s, mean 24.333 s, max 30.000 s over 3 cycles (cycle 1 includes the start-up)\n"
                     "    Cycle      Start s        End s       Time s\n"
                     "        1        0.000       30.000       30.000\n"
                     "        2       30.000       52.000       22.000\n"
                     "        3       52.000       73.000       21.000\n"),
            std::string::npos)
      << out;
  Trace one = testing::exampleCellTrace();
  EXPECT_EQ(summaryTable(one, computeKpis(one)).find("Cycles "), std::string::npos);
}

// What --quiet prints: the faults and the end, the last lines of the table.
// A paced run says how many of its ticks started late, and by how much at most.
TEST(SummaryTable, APacedRunShowsItsLateTicks) {
  Trace t = testing::exampleCellTrace();
  t.time.ticks = 7500;
  EXPECT_EQ(summaryTable(t, computeKpis(t)).find("Late ticks"), std::string::npos) << "not paced";
  t.time.paced = true;
  EXPECT_NE(summaryTable(t, computeKpis(t)).find("Late ticks    none of 7500 ticks started late\n"), std::string::npos);
  t.time.lateTicks = 3;
  t.time.maxLateNs = 12'345'678;
  EXPECT_NE(summaryTable(t, computeKpis(t)).find("Late ticks    3 of 7500 ticks started late (at most 12.346 ms)\n"),
            std::string::npos);
  EXPECT_EQ(lateTicksText(0, 1, 0), "none of 1 tick started late");
}

TEST(SummaryTable, RunOutcomeIsTheTableEnd) {
  Trace t = testing::exampleCellTrace();
  const Kpis k = computeKpis(t);
  const std::string outcome = runOutcome(t, k);
  EXPECT_EQ(outcome, "Faults        1\n     38.000 s  Robot2: gripper lost the bearing (error 17)\n"
                     "Run ended     time limit reached: time limit of 75 s reached\n");
  EXPECT_TRUE(summaryTable(t, k).ends_with(outcome));
}

}  // namespace
}  // namespace virtcom::report
