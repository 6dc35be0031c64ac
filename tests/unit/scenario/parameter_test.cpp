// A device parameter changed in the middle of a run (docs/scenarios.md "Steps", `parameter:`):
// the clamp's command takes longer from the step on, deterministically at the tick the step acts;
// mistakes in the key or the value are diagnostics at the scenario's file:line:col naming the key.
#include <gtest/gtest.h>

#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

// Parts clamped one after the other for 6 s (the station's cycleDone rises once: `cycles: 3`
// keeps the run going to the time limit), the last one starting before 4 s (then the parts run
// out); the clamp closes in 1 s (cell file), a part takes about 1.03 s.
constexpr const char* kParts = "set: {MAIN.start: TRUE}\ncycles: 3\ntime_limit: 6 s\nsteps:\n  - {at: 4 s, facts: {partPresent: false}}\n";

TEST_F(ScenarioTest, ParameterChangeSlowsTheCommandsThatBeginAfterIt) {
  // The first close (0 s .. 1 s) runs with 1 s; the change at 0.5 s does not stretch it; the
  // second close starts at about 1.03 s and takes 2 s, the third one too.
  CaseResult r = run(std::string(kParts) + R"(  - {at: 0.5 s, parameter: {Clamp.commands.1.duration: 2 s}}
expect:
  - {at: 1.02 s, that: "MAIN.parts = 1"}
  - {at: 2.9 s, that: "MAIN.parts = 1 AND Clamp.busy"}
  - {at: 3.1 s, that: "MAIN.parts = 2"}
  - {final: "MAIN.parts = 3"}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, WithoutTheChangeTheSecondPartIsDoneEarly) {
  // The same assertion fails without the change: the assertion can fail.
  CaseResult r = run(std::string(kParts) + "expect:\n  - {at: 2.9 s, that: \"MAIN.parts = 1 AND Clamp.busy\"}\n");
  EXPECT_EQ(r.verdict, Verdict::Fail);
  EXPECT_NE(text(r).find("(MAIN.parts = 2"), std::string::npos) << text(r);
}

TEST_F(ScenarioTest, ParameterChangesOfOneDeviceAddUp) {
  // The power changes on top of the duration changed before it; the duration stays changed:
  // 1 s at 100 W, then twice 2 s at 200 W.
  CaseResult r = run(std::string(kParts) + R"(  - {at: 0.5 s, parameter: {Clamp.commands.1.duration: 2 s}}
  - {at: 0.6 s, parameter: {Clamp.busy_power: 200 W}}
expect:
  - {energy: {device: Clamp, min: 0.89 kJ, max: 0.91 kJ}}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

// The part sensor gets a 0.5 s delay at 1 s: the part taken away at 4 s shows at 4.5 s (the
// PLC, still seeing it, starts a clamp that fails for want of the part: the run goes on).
TEST_F(ScenarioTest, ASensorsDelayChangesMidRun) {
  const std::string parts = std::string("stop_on_device_error: false\n") + kParts;
  const std::string expect = "expect:\n  - {at: 4.3 s, that: MAIN.part}\n  - {at: 4.55 s, that: NOT MAIN.part}\n";
  CaseResult r = run(parts + "  - {at: 1 s, parameter: {PartSensor.delay: 0.5 s}}\n" + expect);
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
  r = run(parts + expect);  // without the change the sensor follows at once
  EXPECT_EQ(r.verdict, Verdict::Fail) << text(r);
  EXPECT_NE(text(r).find("'MAIN.part' is false"), std::string::npos) << text(r);
}

TEST_F(ScenarioTest, ParameterMistakesNameTheKey) {
  const std::string path = write(R"(steps:
  - {at: 1 s, parameter: {Clamp.busy_powr: 200 W}}
  - {at: 1 s, parameter: {Clamp.commands.1.duration: fast}}
  - {at: 1 s, parameter: {Gripper.speed: 1 m/s}}
  - {at: 1 s, parameter: {PartSensor.fact: other}}
  - {at: 1 s, parameter: {Clamp.wiring: x}}
  - {at: 1 s, parameter: {Clamp.commands.7.duration: 1 s}}
)");
  CaseResult r = runCase({path, SIZE_MAX, "test", "test"}, {});
  ASSERT_EQ(r.verdict, Verdict::Error);
  const std::string t = text(r);
  EXPECT_NE(t.find("test.yaml:3:27: error[C011]"), std::string::npos) << t;
  EXPECT_NE(t.find("busy_powr"), std::string::npos) << t;
  EXPECT_NE(t.find("test.yaml:4:54: error[C010]"), std::string::npos) << t;
  EXPECT_NE(t.find("test.yaml:5:27: error[C062]: 'Gripper.speed': expected DEVICE.parameter with a device of the cell (Clamp, PartSensor)"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("test.yaml:6:27: error[C062]: 'PartSensor.fact': a sensor cannot change 'fact' during a run"), std::string::npos)
      << t;
  EXPECT_NE(t.find("test.yaml:7:27: error[C062]: 'Clamp.wiring': 'wiring' is no parameter"), std::string::npos) << t;
  EXPECT_NE(t.find("test.yaml:8:27: error[C062]: 'Clamp.commands.7.duration': the device's entry has no '7' here"), std::string::npos) << t;
}

}  // namespace
}  // namespace virtcom::scenario::test
