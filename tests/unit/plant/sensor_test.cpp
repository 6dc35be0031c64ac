// The sensor device: mirrors a world fact, with delay, inversion and a stuck-output fault.
#include <gtest/gtest.h>

#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

TEST(Sensor, MirrorsAFact) {
  PlantRig rig;
  ASSERT_NE(rig.add("sensor", "S", "fact: partPresent\n"), nullptr) << rig.renderedDiags();
  rig.tick();
  EXPECT_FALSE(rig.getBool("S.value"));
  rig.setFact("partPresent", true);
  rig.tick();
  EXPECT_TRUE(rig.getBool("S.value"));
}

TEST(Sensor, DelayFiltersShortPulsesAndDelaysBothEdges) {
  PlantRig rig;
  Device* s = rig.add("sensor", "S", "fact: f\ndelay: 50 ms\n");
  ASSERT_NE(s, nullptr) << rig.renderedDiags();
  rig.tick();
  rig.setFact("f", true);
  rig.tick();
  const int64_t rise = rig.now;
  EXPECT_EQ(s->nextEventNs(), rise + 50 * kMs);
  rig.tick(49 * kMs);
  EXPECT_FALSE(rig.getBool("S.value"));
  rig.tick();
  EXPECT_TRUE(rig.getBool("S.value"));
  rig.setFact("f", false);
  rig.tick(10 * kMs);
  rig.setFact("f", true);  // 10 ms glitch: never shows
  for (int i = 0; i < 100; ++i) {
    rig.tick();
    EXPECT_TRUE(rig.getBool("S.value"));
  }
  rig.setFact("f", false);
  EXPECT_TRUE(rig.tickUntil([&] { return !rig.getBool("S.value"); }));
}

TEST(Sensor, InvertAndStuckOutput) {
  PlantRig rig;
  Device* s = rig.add("sensor", "S", "fact: f\ninvert: true\n");
  ASSERT_NE(s, nullptr);
  rig.tick();
  EXPECT_TRUE(rig.getBool("S.value"));
  s->faults().stuckOutput = 0;
  rig.tick();
  EXPECT_FALSE(rig.getBool("S.value"));
  rig.setFact("f", true);
  s->faults().stuckOutput = 1;
  rig.tick();
  EXPECT_TRUE(rig.getBool("S.value"));
  s->faults().stuckOutput = -1;
  rig.tick();
  EXPECT_FALSE(rig.getBool("S.value"));
}

TEST(Sensor, ConfigErrors) {
  PlantRig rig;
  EXPECT_EQ(rig.add("sensor", "S", "delay: 5\ninvert: maybe\n"), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("needs 'fact'"), std::string::npos) << out;
  EXPECT_NE(out.find("S.yaml:1:8: error[C010]: 'delay': '5' needs a unit"), std::string::npos) << out;
  EXPECT_NE(out.find("S.yaml:2:9: error[C010]: 'invert' must be true or false"), std::string::npos) << out;
}

}  // namespace
}  // namespace virtcom::plant::test
