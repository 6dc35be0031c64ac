// The positioning-table axis: targetPosition as the command, trapezoidal moves, in-position,
// limits (error 30), named-position labels, energy.
#include <gtest/gtest.h>

#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

const char* kAxisYaml = R"(max_speed: 500 mm/s
acceleration: 1000 mm/s^2
min_position: -100 mm
max_position: 1200 mm
home_position: 0 mm
moving_power: 50 W
accel_power: 20 W
idle_power: 5 W
positions:
  underPress: 1000 mm
)";

class AxisTest : public ::testing::Test {
 protected:
  void SetUp() override {
    axis = rig.add("axis", "AxisX", kAxisYaml);
    ASSERT_NE(axis, nullptr) << rig.renderedDiags();
    rig.prepare();
    rig.tick();
  }
  // Commands a move; returns the error (0 = done) and the time from execute to done/error.
  int move(double mm, int64_t* took = nullptr) {
    rig.setNumber("AxisX.targetPosition", mm);
    rig.setBool("AxisX.execute", true);
    rig.tick();
    const int64_t start = rig.now;
    auto ended = [&] { return rig.getBool("AxisX.done") || rig.getNumber("AxisX.error") != 0; };
    if (!ended()) {
      EXPECT_TRUE(rig.tickUntil(ended));
    }
    if (took) *took = rig.now - start;
    int error = static_cast<int>(rig.getNumber("AxisX.error"));
    rig.setBool("AxisX.execute", false);
    rig.tick();
    return error;
  }
  PlantRig rig;
  Device* axis = nullptr;
};

TEST_F(AxisTest, StartsInPositionAtHome) {
  EXPECT_TRUE(rig.getBool("AxisX.inPosition"));
  EXPECT_EQ(rig.getNumber("AxisX.actualPosition"), 0.0);
  EXPECT_EQ(rig.getNumber("AxisX.actualVelocity"), 0.0);
}

TEST_F(AxisTest, TrapezoidalAndTriangularMoveTimes) {
  int64_t took = 0;
  EXPECT_EQ(move(1000, &took), 0);
  EXPECT_EQ(took, 2500 * kMs);
  EXPECT_DOUBLE_EQ(rig.getNumber("AxisX.actualPosition"), 1000.0);
  EXPECT_EQ(move(900, &took), 0);  // 100 mm back: triangular 632.46 ms
  EXPECT_EQ(took, 633 * kMs);
  EXPECT_EQ(move(900, &took), 0);  // already there
  EXPECT_EQ(took, 0);
}

TEST_F(AxisTest, VelocityAndInPositionDuringTheMove) {
  rig.setNumber("AxisX.targetPosition", -100);
  rig.setBool("AxisX.execute", true);
  rig.tick();
  rig.tick(100 * kMs);
  EXPECT_NEAR(rig.getNumber("AxisX.actualVelocity"), -100.0, 1e-9);  // a t, negative direction
  EXPECT_NEAR(rig.getNumber("AxisX.actualPosition"), -5.0, 1e-9);
  EXPECT_FALSE(rig.getBool("AxisX.inPosition"));
  EXPECT_TRUE(rig.getBool("AxisX.busy"));
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("AxisX.done"); }));
  EXPECT_TRUE(rig.getBool("AxisX.inPosition"));
  EXPECT_EQ(rig.getNumber("AxisX.actualVelocity"), 0.0);
}

TEST_F(AxisTest, TargetOutsideTheLimitsIsError30AndNoMotion) {
  EXPECT_EQ(move(1200.5), 30);
  EXPECT_EQ(move(-100.1), 30);
  EXPECT_EQ(rig.getNumber("AxisX.actualPosition"), 0.0);
  EXPECT_TRUE(rig.getBool("AxisX.inPosition"));
  EXPECT_EQ(move(1200), 0);  // the limits themselves are reachable
  EXPECT_EQ(rig.trace.activities[0].errorCode, 30);
}

TEST_F(AxisTest, LabelsNameKnownPositions) {
  move(1000);
  move(10);
  ASSERT_EQ(rig.trace.activities.size(), 2u);
  EXPECT_EQ(rig.label(rig.trace.activities[0]), "MoveTo underPress");
  EXPECT_EQ(rig.label(rig.trace.activities[1]), "MoveTo");
}

TEST_F(AxisTest, EnergyOfAMove) {
  move(1000);
  // 50 W x 1 m / 0.5 m/s + 20 W x 2 x 0.5 s
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 120.0, 1e-9);
  rig.tick(10 * kS - rig.now);
  rig.finish();
  EXPECT_NEAR(rig.trace.totals[axis->traceIndex()].energyJ, 120.0 + 5.0 * 10, 1e-6);
}

// The position ramps every tick of a move, so event-driven time must step each one (0); once
// done, only execute dropping wakes the axis.
TEST_F(AxisTest, NextEventIsEveryTickWhileMovingThenNone) {
  rig.setNumber("AxisX.targetPosition", 1000);
  rig.setBool("AxisX.execute", true);
  rig.tick();
  EXPECT_EQ(axis->nextEventNs(), 0);
  rig.tick(2500 * kMs);
  EXPECT_TRUE(rig.getBool("AxisX.done"));
  EXPECT_EQ(axis->nextEventNs(), INT64_MAX);
}

TEST_F(AxisTest, ExecuteDroppedMidMoveStillFinishes) {
  rig.setNumber("AxisX.targetPosition", 500);
  rig.setBool("AxisX.execute", true);
  rig.tick();
  rig.setBool("AxisX.execute", false);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("AxisX.done"); }));
  rig.tick();
  EXPECT_FALSE(rig.getBool("AxisX.done"));
  EXPECT_DOUBLE_EQ(rig.getNumber("AxisX.actualPosition"), 500.0);
}

TEST_F(AxisTest, InjectedFaultAndDelay) {
  axis->faults().errorCode = 90;
  axis->faults().errorAtCommand = 1;
  axis->faults().extraDelayNs = 100 * kMs;
  EXPECT_EQ(move(1000), 90);
  int64_t took = 0;
  EXPECT_EQ(move(1000, &took), 0);
  EXPECT_EQ(took, 2600 * kMs);
}

TEST(AxisConfig, DefaultsAndRequiredKeys) {
  PlantRig rig;
  EXPECT_EQ(rig.add("axis", "A", "max_speed: 1 m/s\n"), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("needs 'acceleration'"), std::string::npos) << out;
  EXPECT_NE(out.find("needs 'min_position'"), std::string::npos) << out;
  EXPECT_NE(out.find("needs 'max_position'"), std::string::npos) << out;
}

TEST(AxisConfig, WindowDefaultsToATenthOfAMillimetre) {
  PlantRig rig;
  ASSERT_NE(rig.add("axis", "A", "max_speed: 1 m/s\nacceleration: 1 m/s^2\nmin_position: 0 mm\nmax_position: 1 m\n"), nullptr)
      << rig.renderedDiags();
  rig.tick();
  EXPECT_TRUE(rig.getBool("A.inPosition"));
}

TEST(AxisConfig, HomeOutsideTheLimitsIsReported) {
  PlantRig rig;
  EXPECT_EQ(rig.add("axis", "A",
                    "max_speed: 1 m/s\nacceleration: 1 m/s^2\nmin_position: 0 mm\nmax_position: 1 m\nhome_position: 2 m\n"),
            nullptr);
  EXPECT_NE(rig.renderedDiags().find("A.yaml:5:16: error[C010]: 'home_position' must lie within"), std::string::npos)
      << rig.renderedDiags();
}

}  // namespace
}  // namespace virtcom::plant::test
