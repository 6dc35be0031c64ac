// A small slice of the seed's gearbox cell driven by a scripted "PLC": a bearing arrives on the
// conveyor, Robot1 locks the insert in the press (LockInsert), picks the bearing from the belt
// end (PickBearing), places it (PlaceBearing), the table moves under the press, the press
// presses, a sensor reports it. Checks the facts and the Gantt bars the flow leaves behind.
#include <gtest/gtest.h>

#include "robot_fixture.hpp"

namespace virtcom::plant::test {
namespace {

const char* kRobot1 = R"(max_speed: 1000 mm/s
acceleration: 2000 mm/s^2
tool_change_time: 1 s
locations:
  Home: "0, 0, 500 mm"
  Rack: "-300, 0, 300 mm"
  InsertMagazine: "-300, 300, 200 mm"
  PressTool: { at: "400, 300, 400 mm", zone: Press }
  BeltEnd: "0, -500, 200 mm"
  Seat1: { at: "400, 0, 150 mm", zone: Workpiece }
tools:
  InsertHandler: { kind: insert_handler, mass: 0.8 kg, close_time: 0.2 s, open_time: 0.2 s, magazine: Rack }
  CentricGripper1: { kind: centric_gripper, mass: 1 kg, close_time: 0.3 s, open_time: 0.3 s, magazine: Rack }
parts:
  insert: { mass: 1.5 kg, tool: InsertHandler }
  bearingAtPickup: { mass: 0.6 kg, tool: CentricGripper1 }
procedures:
  1: { name: LockInsert, steps: [move Rack, attach InsertHandler, move InsertMagazine, grip insert, move PressTool, release insert, set insertLocked, move Rack, detach, move Home] }
  2: { name: PickBearing, steps: [move Rack, attach CentricGripper1, move BeltEnd, grip bearingAtPickup] }
  3: { name: PlaceBearing, steps: [move Seat1, release bearingAtPickup, set bearing1Placed, move Home] }
  4: { name: PickBearingWithInsertHandler, steps: [move Rack, attach InsertHandler, move BeltEnd, grip bearingAtPickup] }
  5: { name: GripInsertTwice, steps: [move Rack, attach InsertHandler, move InsertMagazine, grip insert, grip insert] }
)";

class GearboxFlow : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(rig.add("robot", "Robot1", kRobot1), nullptr) << rig.renderedDiags();
    ASSERT_NE(rig.add("conveyor", "Belt", "speed: 200 mm/s\nlength: 1 m\npart_length: 100 mm\ninitial_parts: [0 mm]\nend_fact: bearingAtPickup\n"), nullptr)
        << rig.renderedDiags();
    ASSERT_NE(rig.add("axis", "AxisX", "max_speed: 200 mm/s\nacceleration: 1 m/s^2\nmin_position: 0 mm\nmax_position: 500 mm\n"), nullptr);
    ASSERT_NE(rig.add("press", "Press", "programs:\n  1: { name: PressBearing1, approach_time: 0.5 s, press_time: 1 s, return_time: 0.5 s, force: 20 kN, requires: [bearing1Placed], sets: [bearing1Pressed] }\n"),
              nullptr);
    ASSERT_NE(rig.add("sensor", "PressedSensor", "fact: bearing1Pressed\n"), nullptr);
    rig.setFact("insert", true);
    rig.prepare();
  }
  int command(const std::string& dev, const std::string& port, double value) {
    rig.setNumber(dev + "." + port, value);
    rig.setBool(dev + ".execute", true);
    EXPECT_TRUE(rig.tickUntil([&] { return rig.getBool(dev + ".done") || rig.getNumber(dev + ".error") != 0; }));
    int e = static_cast<int>(rig.getNumber(dev + ".error"));
    rig.setBool(dev + ".execute", false);
    rig.tick();
    return e;
  }
  PlantRig rig;
};

TEST_F(GearboxFlow, InsertBearingPressInSequence) {
  rig.setBool("Belt.run", true);
  EXPECT_EQ(command("Robot1", "procedureNumber", 1), 0);  // LockInsert (belt keeps running)
  EXPECT_TRUE(rig.fact("insertLocked"));
  EXPECT_FALSE(rig.fact("insert"));
  ASSERT_TRUE(rig.fact("bearingAtPickup"));
  EXPECT_EQ(command("Robot1", "procedureNumber", 2), 0);  // PickBearing from the belt end
  rig.tick();
  EXPECT_FALSE(rig.getBool("Belt.moving") && rig.fact("bearingAtPickup"));
  EXPECT_EQ(command("Press", "programNumber", 1), 20);    // not placed yet
  EXPECT_EQ(command("Robot1", "procedureNumber", 3), 0);  // PlaceBearing
  EXPECT_EQ(command("AxisX", "targetPosition", 450), 0);
  EXPECT_FALSE(rig.getBool("PressedSensor.value"));
  EXPECT_EQ(command("Press", "programNumber", 1), 0);
  EXPECT_TRUE(rig.getBool("PressedSensor.value"));
  EXPECT_TRUE(rig.trace.collisions.empty());

  std::vector<std::string> labels;
  for (const auto& a : rig.trace.activities)
    if (rig.trace.devices[a.device].type != "conveyor") labels.push_back(rig.label(a));
  EXPECT_EQ(labels, (std::vector<std::string>{"LockInsert", "PickBearing", "PressBearing1", "PlaceBearing", "MoveTo",
                                              "PressBearing1"}));
}

TEST_F(GearboxFlow, APartRestrictedToAnotherToolIsError21) {
  rig.setBool("Belt.run", true);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.fact("bearingAtPickup"); }));
  EXPECT_EQ(command("Robot1", "procedureNumber", 4), 21);
  EXPECT_TRUE(rig.fact("bearingAtPickup"));  // still on the belt
}

TEST_F(GearboxFlow, GrippingWhileHoldingIsError21) {
  EXPECT_EQ(command("Robot1", "procedureNumber", 5), 21);
  EXPECT_FALSE(rig.fact("insert"));  // the first grip took it
}

}  // namespace
}  // namespace virtcom::plant::test
