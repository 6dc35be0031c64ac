// The servo press: program phases and their outputs, the locked-insert rule (error 40),
// requires/sets facts, energy.
#include <gtest/gtest.h>

#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

const char* kPressYaml = R"(stroke: 100 mm
idle_power: 10 W
press_power: 2 kW
programs:
  1: { name: PressBearing1, approach_time: 1 s, press_time: 0.5 s, hold_time: 0.25 s, return_time: 1 s, force: 20 kN, requires: [bearing1Placed], sets: [bearing1Pressed] }
  2: { name: PressPin, press_time: 0.2 s, force: 5 kN, clears: [pinLoose] }
)";

class PressTest : public ::testing::Test {
 protected:
  void SetUp() override {
    press = rig.add("press", "Press", kPressYaml);
    ASSERT_NE(press, nullptr) << rig.renderedDiags();
    rig.prepare();
    rig.tick();
  }
  int run(int program, int64_t* took = nullptr) {
    rig.setNumber("Press.programNumber", program);
    rig.setBool("Press.execute", true);
    rig.tick();
    const int64_t start = rig.now;
    auto ended = [&] { return rig.getBool("Press.done") || rig.getNumber("Press.error") != 0; };
    if (!ended()) {
      EXPECT_TRUE(rig.tickUntil(ended));
    }
    if (took) *took = rig.now - start;
    int e = static_cast<int>(rig.getNumber("Press.error"));
    rig.setBool("Press.execute", false);
    rig.tick();
    return e;
  }
  PlantRig rig;
  Device* press = nullptr;
};

TEST_F(PressTest, WithoutALockedInsertIsError40) {
  rig.setFact("bearing1Placed", true);
  EXPECT_EQ(run(1), 40);
  EXPECT_FALSE(rig.fact("bearing1Pressed"));
  EXPECT_EQ(rig.trace.activities[0].errorCode, 40);
}

TEST_F(PressTest, MissingRequiredFactIsError20) {
  rig.setFact("insertLocked", true);
  EXPECT_EQ(run(1), 20);
}

TEST_F(PressTest, ProgramTakesItsPhasesAndSetsFacts) {
  rig.setFact("insertLocked", true);
  rig.setFact("bearing1Placed", true);
  int64_t took = 0;
  EXPECT_EQ(run(1, &took), 0);
  EXPECT_EQ(took, 2750 * kMs);
  EXPECT_TRUE(rig.fact("bearing1Pressed"));
  EXPECT_EQ(rig.label(rig.trace.activities[0]), "PressBearing1");
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 2000.0 * 0.75, 1e-9);
}

TEST_F(PressTest, ForceAndPositionFollowThePhases) {
  rig.setFact("insertLocked", true);
  rig.setFact("bearing1Placed", true);
  rig.setNumber("Press.programNumber", 1);
  rig.setBool("Press.execute", true);
  rig.tick();
  EXPECT_EQ(rig.getNumber("Press.actualForce"), 0.0);
  rig.tick(500 * kMs);  // approach half way
  EXPECT_NEAR(rig.getNumber("Press.position"), 50.0, 1e-9);
  EXPECT_EQ(rig.getNumber("Press.actualForce"), 0.0);
  rig.tick(750 * kMs);  // half of the press phase
  EXPECT_NEAR(rig.getNumber("Press.actualForce"), 10000.0, 1e-6);
  EXPECT_NEAR(rig.getNumber("Press.position"), 100.0, 1e-9);
  rig.tick(400 * kMs);  // holding
  EXPECT_NEAR(rig.getNumber("Press.actualForce"), 20000.0, 1e-6);
  rig.tick(600 * kMs);  // returning, 0.5 s in (t = 2.25 s)
  EXPECT_EQ(rig.getNumber("Press.actualForce"), 0.0);
  EXPECT_NEAR(rig.getNumber("Press.position"), 50.0, 1e-9);
  EXPECT_FALSE(rig.fact("bearing1Pressed"));  // effects at the end
  rig.tick(500 * kMs);
  EXPECT_TRUE(rig.getBool("Press.done"));
  EXPECT_EQ(rig.getNumber("Press.position"), 0.0);
}

// Event-driven time may skip ticks only while no output changes: the stroke and force ramps vary
// every tick (0: step the next one), the hold phase holds until the return starts.
TEST_F(PressTest, NextEventIsEveryTickWhileRampingAndTheReturnWhileHolding) {
  rig.setFact("insertLocked", true);
  rig.setFact("bearing1Placed", true);
  EXPECT_EQ(press->nextEventNs(), INT64_MAX);  // idle, execute low: only inputs wake it
  rig.setNumber("Press.programNumber", 1);
  rig.setBool("Press.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  EXPECT_EQ(press->nextEventNs(), 0);  // approach: the position ramps
  rig.tick(1200 * kMs);
  EXPECT_EQ(press->nextEventNs(), 0);  // press: the force ramps
  rig.tick(400 * kMs);
  EXPECT_EQ(press->nextEventNs(), start + 1750 * kMs);  // holding until the return
  rig.tick(300 * kMs);
  EXPECT_EQ(press->nextEventNs(), 0);  // returning
}

TEST_F(PressTest, OptionalPhasesDefaultToZeroAndClearsWork) {
  rig.setFact("insertLocked", true);
  rig.setFact("pinLoose", true);
  int64_t took = 0;
  EXPECT_EQ(run(2, &took), 0);
  EXPECT_EQ(took, 200 * kMs);
  EXPECT_FALSE(rig.fact("pinLoose"));
}

TEST_F(PressTest, UnknownProgramIsError10) { EXPECT_EQ(run(7), 10); }

TEST_F(PressTest, CustomInsertFact) {
  PlantRig r2;
  ASSERT_NE(r2.add("press", "P", "insert_fact: punchMounted\nprograms:\n  1: { name: X, press_time: 1 s, force: 1 kN }\n"), nullptr)
      << r2.renderedDiags();
  r2.prepare();
  r2.setFact("insertLocked", true);
  r2.setNumber("P.programNumber", 1);
  r2.setBool("P.execute", true);
  r2.tick();
  EXPECT_EQ(r2.getNumber("P.error"), 40);
}

TEST_F(PressTest, EnergyTotals) {
  rig.setFact("insertLocked", true);
  run(2);
  rig.tick(10 * kS - rig.now);
  rig.finish();
  EXPECT_NEAR(rig.trace.totals[press->traceIndex()].energyJ, 10.0 * 10 + 2000 * 0.2, 1e-6);
  EXPECT_EQ(rig.trace.totals[press->traceIndex()].busyNs, 200 * kMs);
}

TEST(PressConfig, ProgramErrorsPointAtTheirLines) {
  PlantRig rig;
  EXPECT_EQ(rig.add("press", "P", "programs:\n  1: { name: X, press_time: 1 s }\n  2: { name: Y, press_time: 1 s, force: 1 kN, sets: pressed, foo: 1 }\n"),
            nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("P.yaml:2:6: error[C010]: program 1 of press 'P' needs 'force'"), std::string::npos) << out;
  EXPECT_NE(out.find("P.yaml:3:62: error[C011]: unknown key 'foo'"), std::string::npos) << out;
}

// A negative phase time is reported at its value with the key's name (issue 16: it used to be
// reported at the `{` of the program, as "program times", whichever key it was).
TEST(PressConfig, NegativeTimeIsReportedAtItsKey) {
  PlantRig rig;
  EXPECT_EQ(rig.add("press", "P", "programs:\n  1: { name: X, press_time: -1 s, return_time: -0.5 s, force: 1 kN }\n"),
            nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("P.yaml:2:29: error[C010]: 'press_time' must not be negative (got '-1 s')"), std::string::npos) << out;
  EXPECT_NE(out.find("P.yaml:2:48: error[C010]: 'return_time' must not be negative (got '-0.5 s')"), std::string::npos)
      << out;
  EXPECT_EQ(out.find("program times"), std::string::npos) << out;
}

}  // namespace
}  // namespace virtcom::plant::test
