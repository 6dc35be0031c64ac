// The generic timed device: named command port, durations, requires/sets/clears, power.
#include <gtest/gtest.h>

#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

const char* kClampYaml = R"(command_port: clampCommand
busy_power: 100 W
commands:
  1: { name: LockInsert, duration: 0.8 s, requires: [insertInPress], sets: [insertLocked] }
  2: { name: UnlockInsert, duration: 0.4 s, clears: [insertLocked] }
)";

TEST(TimedDevice, RunsCommandsThroughTheHandshake) {
  PlantRig rig;
  Device* d = rig.add("timed", "Clamp", kClampYaml);
  ASSERT_NE(d, nullptr) << rig.renderedDiags();
  EXPECT_EQ(d->ports()[0].name, "clampCommand");
  rig.prepare();
  rig.setFact("insertInPress", true);
  rig.setNumber("Clamp.clampCommand", 1);
  rig.setBool("Clamp.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  EXPECT_TRUE(rig.getBool("Clamp.busy"));
  EXPECT_EQ(d->nextEventNs(), start + 800 * kMs);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("Clamp.done"); }));
  EXPECT_EQ(rig.now - start, 800 * kMs);
  EXPECT_TRUE(rig.fact("insertLocked"));
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 80.0, 1e-9);
  rig.setBool("Clamp.execute", false);
  rig.tick();
  EXPECT_FALSE(rig.getBool("Clamp.done"));
  rig.setNumber("Clamp.clampCommand", 2);
  rig.setBool("Clamp.execute", true);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("Clamp.done"); }));
  EXPECT_FALSE(rig.fact("insertLocked"));
}

TEST(TimedDevice, RequiresIsError20AndUnknownIs10) {
  PlantRig rig;
  ASSERT_NE(rig.add("timed", "Clamp", kClampYaml), nullptr);
  rig.prepare();
  rig.setNumber("Clamp.clampCommand", 1);
  rig.setBool("Clamp.execute", true);
  rig.tick();
  EXPECT_EQ(rig.getNumber("Clamp.error"), 20);
  rig.setBool("Clamp.execute", false);
  rig.tick();
  EXPECT_EQ(rig.getNumber("Clamp.error"), 0);
  rig.setNumber("Clamp.clampCommand", 3);
  rig.setBool("Clamp.execute", true);
  rig.tick();
  EXPECT_EQ(rig.getNumber("Clamp.error"), 10);
}

TEST(TimedDevice, DefaultCommandPortIsProgramNumber) {
  PlantRig rig;
  Device* d = rig.add("timed", "T", "commands:\n  5: { name: Feed, duration: 2 s }\n");
  ASSERT_NE(d, nullptr) << rig.renderedDiags();
  EXPECT_EQ(d->ports()[0].name, "programNumber");
  EXPECT_EQ(d->ports()[0].type, ElemType::Int);
}

TEST(TimedDevice, ConfigErrors) {
  PlantRig rig;
  EXPECT_EQ(rig.add("timed", "T", "command_port: done\ncommands:\n  x: { name: Feed, duration: -1 s }\n"), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("T.yaml:1:15: error[C010]: 'command_port' must be a new port name"), std::string::npos) << out;
  EXPECT_NE(out.find("T.yaml:3:3: error[C010]: command number 'x'"), std::string::npos) << out;
  EXPECT_NE(out.find("T.yaml:3:30: error[C010]: 'duration' must not be negative"), std::string::npos) << out;
}

}  // namespace
}  // namespace virtcom::plant::test
