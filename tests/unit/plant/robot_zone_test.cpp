// Two robots in a shared workspace: zones are occupied from the start of the move into a
// location until the end of the move out of it; overlapping occupation is a collision recorded
// in the trace with both activity labels (seed Figure 10).
#include <gtest/gtest.h>

#include "robot_fixture.hpp"

namespace virtcom::plant::test {
namespace {

const char* kR1 = R"(max_speed: 1000 mm/s
acceleration: 1000 mm/s^2
locations:
  Home: "0, 0, 0 mm"
  Stud: { at: "1000, 0, 0 mm", zone: Workpiece }
procedures:
  1: { name: ScrewStud1, steps: [move Stud, wait 2 s] }
  2: { name: R1Home, steps: [move Home] }
)";

const char* kR2 = R"(max_speed: 1000 mm/s
acceleration: 1000 mm/s^2
locations:
  Home: "2000, 0, 0 mm"
  Seat: { at: "1000, 100, 0 mm", zone: Workpiece }
  Seat2: { at: "1000, 200, 0 mm", zone: Workpiece }
procedures:
  1: { name: PlaceBearing1, steps: [move Seat, move Seat2, wait 1 s] }
  2: { name: R2Home, steps: [move Home] }
)";

class RobotZones : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(rig.add("robot", "R1", kR1), nullptr) << rig.renderedDiags();
    ASSERT_NE(rig.add("robot", "R2", kR2), nullptr) << rig.renderedDiags();
    rig.prepare();
    rig.tick();
  }
  void start(const std::string& dev, int n) {
    rig.setNumber(dev + ".procedureNumber", n);
    rig.setBool(dev + ".execute", true);
  }
  PlantRig rig;
};

TEST_F(RobotZones, OverlappingOccupationIsACollisionWithBothLabels) {
  start("R1", 1);
  rig.tick();
  rig.tick(500 * kMs);
  start("R2", 1);  // R1 is moving into the zone already
  rig.tick();
  ASSERT_EQ(rig.trace.collisions.size(), 1u);
  const CollisionRecord& c = rig.trace.collisions[0];
  EXPECT_EQ(rig.trace.labels[c.zone], "Workpiece");
  EXPECT_EQ(rig.trace.devices[c.deviceA].name, "R1");
  EXPECT_EQ(rig.trace.devices[c.deviceB].name, "R2");
  EXPECT_EQ(rig.trace.labels[c.activityA], "ScrewStud1");
  EXPECT_EQ(rig.trace.labels[c.activityB], "PlaceBearing1");
  EXPECT_EQ(c.timeNs, rig.now);
  EXPECT_TRUE(rig.world.collided());
  // moving within the zone (Seat -> Seat2) is no new entry
  rig.tickUntil([&] { return rig.getBool("R2.done"); });
  EXPECT_EQ(rig.trace.collisions.size(), 1u);
}

TEST_F(RobotZones, SequencedUseOfTheZoneIsNoCollision) {
  EXPECT_EQ(runProcedure(rig, "R1", 1), 0);
  EXPECT_EQ(runProcedure(rig, "R1", 2), 0);  // out of the zone at the end of this move
  EXPECT_EQ(runProcedure(rig, "R2", 1), 0);
  EXPECT_EQ(runProcedure(rig, "R2", 2), 0);
  EXPECT_EQ(runProcedure(rig, "R1", 1), 0);
  EXPECT_TRUE(rig.trace.collisions.empty());
}

TEST_F(RobotZones, TheZoneIsHeldUntilTheEndOfTheMoveOut) {
  EXPECT_EQ(runProcedure(rig, "R1", 1), 0);
  start("R1", 2);  // leaving: 1 s accel + 0 s cruise... still inside until the move ends
  rig.tick();
  rig.tick(1500 * kMs);
  start("R2", 1);
  rig.tick();
  ASSERT_EQ(rig.trace.collisions.size(), 1u);
  EXPECT_EQ(rig.trace.labels[rig.trace.collisions[0].activityA], "R1Home");
}

TEST_F(RobotZones, ARobotIdlingInTheZoneStillOccupiesIt) {
  EXPECT_EQ(runProcedure(rig, "R1", 1), 0);
  rig.tick(5 * kS);
  EXPECT_EQ(runProcedure(rig, "R2", 1), 0);
  ASSERT_EQ(rig.trace.collisions.size(), 1u);
  EXPECT_EQ(rig.trace.labels[rig.trace.collisions[0].activityA], "ScrewStud1");
}

TEST(RobotZoneHome, StartingAtAHomeInsideAZoneOccupiesItAsIdle) {
  PlantRig rig;
  ASSERT_NE(rig.add("robot", "R1", R"(max_speed: 1 m/s
acceleration: 1 m/s^2
locations:
  Park: { at: "0, 0, 0 mm", zone: Z }
procedures:
  1: { name: Noop, steps: [] }
)"),
            nullptr);
  ASSERT_NE(rig.add("robot", "R2", R"(max_speed: 1 m/s
acceleration: 1 m/s^2
locations:
  Home: "0, 500, 0 mm"
  In: { at: "0, 0, 0 mm", zone: Z }
procedures:
  1: { name: Enter, steps: [move In] }
)"),
            nullptr);
  rig.prepare();
  EXPECT_EQ(runProcedure(rig, "R2", 1), 0);
  ASSERT_EQ(rig.trace.collisions.size(), 1u);
  EXPECT_EQ(rig.trace.labels[rig.trace.collisions[0].activityA], "Idle");
  EXPECT_EQ(rig.trace.labels[rig.trace.collisions[0].activityB], "Enter");
}

}  // namespace
}  // namespace virtcom::plant::test
