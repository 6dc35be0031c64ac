#pragma once
// Test-only: the robot used by the robot tests (one axis-aligned layout so move times are easy
// to compute by hand) and a helper that runs one procedure through the full handshake.
#include <string>

#include "plant_rig.hpp"

namespace virtcom::plant::test {

// 500 mm/s, 1000 mm/s^2: a move of d >= 250 mm takes 0.5 + (d - 250 mm)/(500 mm/s) + 0.5 s.
inline const char* kRobotYaml = R"(max_speed: 500 mm/s
acceleration: 1000 mm/s^2
payload_capacity: 10 kg
idle_power: 100 W
moving_power: 400 W
accel_power: 200 W
home: Home
tool_change_time: 1 s
locations:
  Home: "0, 0, 0 mm"
  Far: "1000, 0, 0 mm"
  Near: "100, 0, 0 mm"
  Magazine: "0, 300, 400 mm"
  Table: { at: "1000, 0, 0 mm", zone: Shared }
tools:
  Gripper1: { kind: parallel_gripper, mass: 1 kg, close_time: 0.2 s, open_time: 0.1 s, magazine: Magazine }
  Screwer: { kind: screwer, mass: 2 kg, rundown_time: 1.5 s, final_torque: 12 Nm }
parts:
  bearing1: 0.8 kg
procedures:
  1: { name: GoFar, steps: [move Far] }
  2: { name: GoHome, steps: [move Home] }
  3: { name: GoNear, steps: [move Near] }
  4: { name: AttachGripper, steps: [move Magazine, attach Gripper1] }
  5: { name: AttachHere, steps: [attach Gripper1] }
  6: { name: Detach, steps: [detach] }
  7: { name: PickBearing1, steps: [grip bearing1] }
  8: { name: PlaceBearing1, steps: [release bearing1, set bearing1Placed] }
  9: { name: AttachScrewer, steps: [attach Screwer] }
  10: { name: ScrewStud1, steps: [screw stud1] }
  11: { name: NeedsInsert, steps: [require insertLocked, wait 0.5 s, set done1] }
  12: { name: Empty, steps: [] }
  13: { name: ClearIt, steps: [clear flag] }
  14: { name: GoTable, steps: [move Table] }
)";

// Runs procedure `number` on `dev`: execute until done or error, then drops execute and ticks
// once. Returns the error code seen (0 = done) and the virtual time at done/error in *atNs.
inline int runProcedure(PlantRig& rig, const std::string& dev, int number, int64_t* atNs = nullptr,
                        int64_t limitNs = 60 * kS) {
  rig.setNumber(dev + ".procedureNumber", number);
  rig.setBool(dev + ".execute", true);
  bool ended = rig.tickUntil([&] { return rig.getBool(dev + ".done") || rig.getNumber(dev + ".error") != 0; }, limitNs);
  EXPECT_TRUE(ended) << "procedure " << number << " did not end";
  if (atNs) *atNs = rig.now;
  int error = static_cast<int>(rig.getNumber(dev + ".error"));
  rig.setBool(dev + ".execute", false);
  rig.tick();
  return error;
}

}  // namespace virtcom::plant::test
