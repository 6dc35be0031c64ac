// Robot motion: exact trapezoidal/triangular durations, travel time depending on where the
// robot comes from, interpolated actual positions, move energy and totals.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/robot.hpp"
#include "robot_fixture.hpp"

namespace virtcom::plant::test {
namespace {

class RobotMotion : public ::testing::Test {
 protected:
  void SetUp() override {
    robot = rig.add("robot", "R1", kRobotYaml);
    ASSERT_NE(robot, nullptr) << rig.renderedDiags();
    rig.prepare();
  }
  // Duration from the execute tick to the done tick.
  int64_t timed(int number) {
    const int64_t start = rig.now + kMs;
    int64_t at = 0;
    EXPECT_EQ(runProcedure(rig, "R1", number, &at), 0);
    return at - start;
  }
  PlantRig rig;
  Device* robot = nullptr;
};

TEST_F(RobotMotion, TravelTimeDependsOnThePreviousLocation) {
  EXPECT_EQ(timed(1), 2500 * kMs);  // Home -> Far: 1000 mm, 0.5 + 1.5 + 0.5 s
  EXPECT_EQ(timed(3), 2300 * kMs);  // Far -> Near: 900 mm, 0.5 + 1.3 + 0.5 s
  EXPECT_EQ(timed(2), 633 * kMs);   // Near -> Home: 100 mm triangular, 2 sqrt(0.1) s = 632.46 ms
  EXPECT_EQ(timed(3), 633 * kMs);   // Home -> Near
  EXPECT_EQ(timed(3), 0);           // already there: no motion, done at once
}

TEST_F(RobotMotion, ActivityEndsAtTheExactEndWhenTicksAlign) {
  runProcedure(rig, "R1", 1, nullptr);
  const ActivityRecord& a = rig.trace.activities[0];
  EXPECT_EQ(a.endNs - a.startNs, 2500 * kMs);
}

TEST_F(RobotMotion, DoneRisesAtTheFirstTickAfterTheEndWithCoarseTicks) {
  rig.setNumber("R1.procedureNumber", 3);  // 632.455532 ms
  rig.setBool("R1.execute", true);
  rig.tick(100 * kMs);
  const int64_t start = rig.now;
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("R1.done"); }, 10 * kS, 100 * kMs));
  EXPECT_EQ(rig.now - start, 700 * kMs);
}

TEST_F(RobotMotion, ActualPositionFollowsTheProfile) {
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 0.0);
  rig.tick(500 * kMs);
  EXPECT_NEAR(rig.getNumber("R1.actualX"), 125.0, 1e-9);  // end of acceleration
  rig.tick(500 * kMs);
  EXPECT_NEAR(rig.getNumber("R1.actualX"), 375.0, 1e-9);  // cruising at 500 mm/s
  rig.tick(1250 * kMs);
  EXPECT_NEAR(rig.getNumber("R1.actualX"), 968.75, 1e-9);  // 0.25 s before the end: 1000 - a t^2/2
  EXPECT_EQ(rig.getNumber("R1.actualY"), 0.0);
  rig.tick(250 * kMs);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 1000.0);
  EXPECT_TRUE(rig.getBool("R1.done"));
}

TEST_F(RobotMotion, DiagonalMoveUsesTheStraightLineDistance) {
  // Home -> Magazine: (0, 300, 400) mm = 500 mm: 0.5 + 0.5 + 0.5 s; then 1 s tool change.
  EXPECT_EQ(timed(4), 2500 * kMs);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualY"), 300.0);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualZ"), 400.0);
}

TEST_F(RobotMotion, MoveEnergyFollowsTheFormula) {
  runProcedure(rig, "R1", 1);
  // (1 + 0/10) x (400 W x 1 m / 0.5 m/s + 200 W x 2 x 0.5 s) = 800 + 200 J
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 1000.0, 1e-9);
}

TEST_F(RobotMotion, PayloadScalesMoveEnergy) {
  runProcedure(rig, "R1", 4);  // to the magazine (500 mm, no payload) and attach 1 kg gripper
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 400 * 1.0 + 200 * 1.0, 1e-9);
  rig.setFact("bearing1", true);
  runProcedure(rig, "R1", 7);  // grip: no move, no move energy
  EXPECT_EQ(rig.trace.activities[1].energyJ, 0.0);
  runProcedure(rig, "R1", 2);  // back home, 500 mm with 1 kg tool + 0.8 kg part
  EXPECT_NEAR(rig.trace.activities[2].energyJ, (1 + 1.8 / 10) * (400 * 1.0 + 200 * 1.0), 1e-9);
}

TEST_F(RobotMotion, TotalsIncludeIdlePowerOverTheWholeRun) {
  runProcedure(rig, "R1", 1);  // 1 ms idle, 2.5 s move, 1 ms to drop done
  rig.tick(10 * kS - rig.now);
  rig.finish();
  const DeviceTotals& t = rig.trace.totals[robot->traceIndex()];
  EXPECT_NEAR(t.energyJ, 100.0 * 10 + 1000.0, 1e-6);
  EXPECT_EQ(t.busyNs, 2500 * kMs);
}

TEST_F(RobotMotion, TotalsCountARunningProcedure) {
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  rig.tick(kS);
  rig.finish();
  EXPECT_EQ(rig.trace.totals[robot->traceIndex()].busyNs, kS);
  EXPECT_EQ(rig.trace.activities[0].endNs, -1);
}

TEST_F(RobotMotion, SkippingTimeGivesTheSameResultAsFineTicks) {
  PlantRig fine, coarse;
  ASSERT_NE(fine.add("robot", "R1", kRobotYaml), nullptr);
  Device* c = coarse.add("robot", "R1", kRobotYaml);
  ASSERT_NE(c, nullptr);
  for (int n : {1, 3, 2, 4}) runProcedure(fine, "R1", n);
  coarse.prepare();
  for (int n : {1, 3, 2, 4}) {
    coarse.setNumber("R1.procedureNumber", n);
    coarse.setBool("R1.execute", true);
    coarse.tick();
    // a move's outputs change every tick (nextEventNs 0): 1 ms ticks then, jumps over the rest
    while (!coarse.getBool("R1.done")) coarse.tick(c->nextEventNs() > coarse.now ? c->nextEventNs() - coarse.now : kMs);
    coarse.setBool("R1.execute", false);
    coarse.tick();
  }
  ASSERT_EQ(fine.trace.activities.size(), coarse.trace.activities.size());
  for (size_t i = 0; i < fine.trace.activities.size(); ++i) {
    const auto& a = fine.trace.activities[i];
    const auto& b = coarse.trace.activities[i];
    // jumping to nextEventNs() ends at most where 1 ms ticks end
    EXPECT_GE(a.endNs - a.startNs, b.endNs - b.startNs) << i;
    EXPECT_LT(a.endNs - a.startNs, b.endNs - b.startNs + kMs) << i;
    EXPECT_DOUBLE_EQ(a.energyJ, b.energyJ);
  }
}

}  // namespace
}  // namespace virtcom::plant::test
