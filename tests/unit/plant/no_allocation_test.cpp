// The per-tick path is real-time clean (STYLE rule 7): once the trace has room for its records,
// stepping devices through whole commands allocates nothing (tests/support/allocation_counter).
#include <gtest/gtest.h>

#include "robot_fixture.hpp"
#include "support/allocation_counter.hpp"

namespace virtcom::plant::test {
namespace {

const char* kCellYaml[][3] = {
    {"axis", "AxisX", "max_speed: 500 mm/s\nacceleration: 1 m/s^2\nmin_position: 0 mm\nmax_position: 1 m\n"},
    {"press", "Press", "stroke: 50 mm\nprograms:\n  1: { name: P, approach_time: 0.1 s, press_time: 0.2 s, force: 1 kN, sets: [pressed] }\n"},
    {"timed", "Clamp", "commands:\n  1: { name: LockInsert, duration: 0.3 s, sets: [insertLocked] }\n"},
    {"conveyor", "Belt", "speed: 100 mm/s\nlength: 1 m\nspawn_interval: 1 s\nend_fact: atEnd\nsensors:\n  s1: 500 mm\n"},
    {"sensor", "S", "fact: insertLocked\ndelay: 10 ms\n"},
    {"conveyor", "Sorter",
     "speed: 200 mm/s\nlength: 1 m\nspawn_interval: 1 s\npart_kinds: [a, b]\ndischarge: true\n"
     "sensors:\n  s: {at: 500 mm, detects: [a]}\npushers:\n  p: 600 mm\n"},
    {"tank", "Tank", "capacity: 100 l\nheat_loss: 5 W/K\n"},
    {"valve", "Fill", "to: Tank\nflow: 50 l/min\ntravel_time: 2 s\n"},
    {"pump", "Drain", "from: Tank\nflow: 20 l/min\npower: 300 W\n"},
    {"heater", "Heat", "tank: Tank\npower: 2 kW\n"},
    {"level_switch", "High", "tank: Tank\nabove: 90 %\nhysteresis: 5 %\n"},
    {"temperature_sensor", "TT", "tank: Tank\nlag: 5 s\n"},
};

TEST(NoAllocation, SteppingDevicesThroughCommandsDoesNotAllocate) {
  PlantRig rig;
  ASSERT_NE(rig.add("robot", "R1", kRobotYaml), nullptr);
  for (const auto& d : kCellYaml) ASSERT_NE(rig.add(d[0], d[1], d[2]), nullptr) << rig.renderedDiags();
  rig.prepare();
  rig.trace.activities.reserve(1000);
  rig.setFact("bearing1", true);
  rig.setFact("stud1", true);
  rig.setBool("Belt.run", true);
  rig.setBool("Sorter.run", true);
  rig.tick();
  const TagId processCommands[] = {rig.tagOf("Fill.open"), rig.tagOf("Drain.run"), rig.tagOf("Heat.on"),
                                   rig.tagOf("Sorter.p")};

  const TagId robotCmd = rig.tagOf("R1.procedureNumber"), axisCmd = rig.tagOf("AxisX.targetPosition");
  const TagId pressCmd = rig.tagOf("Press.programNumber"), clampCmd = rig.tagOf("Clamp.programNumber");
  const TagId executes[] = {rig.tagOf("R1.execute"), rig.tagOf("AxisX.execute"), rig.tagOf("Press.execute"),
                            rig.tagOf("Clamp.execute")};
  const virtcom::test::AllocationCounter allocations;
  for (int n : {1, 4, 7, 2, 8, 3, 99}) {  // moves, tools, grip/release, an unknown number
    rig.bus.setNumber(robotCmd, n);
    rig.bus.setNumber(axisCmd, n * 10.0);
    rig.bus.setNumber(pressCmd, 1);
    rig.bus.setNumber(clampCmd, 1);
    for (TagId e : executes) rig.bus.setBool(e, true);
    for (TagId c : processCommands) rig.bus.setBool(c, n % 2 == 1);  // on and off: activities open and close
    for (int i = 0; i < 4000; ++i) rig.tick();
    for (TagId e : executes) rig.bus.setBool(e, false);
    rig.tick();
  }
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_GE(rig.trace.activities.size(), 7u * 4);
}

}  // namespace
}  // namespace virtcom::plant::test
