// Steps and faults of docs/scenarios.md on the station cell: set and force on the time line and
// on conditions, release, world facts, device faults (error at the Nth command, sensor stuck,
// done stuck caught by the PLC's watchdog) and a power loss with a warm restart.
#include <gtest/gtest.h>

#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

TEST_F(ScenarioTest, SetAtATimeStartsTheCycleThen) {
  CaseResult r = run(R"(steps:
  - {at: 2 s, set: {MAIN.start: TRUE}}
expect:
  - {at: 1.99 s, that: "MAIN.state = 0"}
  - {cycle_time: {min: 3.02 s, max: 3.04 s}}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, StepOnAConditionActsOnceItHolds) {
  // The clamp's busy output makes the step release the force that held the part sensor off.
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
steps:
  - {at: 0 s, force: {MAIN.part: FALSE}}
  - {at: 1 s, release: MAIN.part}
  - {when: "MAIN.state = 1", set: {MAIN.cmd: 1}}
expect:
  - {at: 0.99 s, that: "MAIN.state = 0 AND PartSensor.value"}
  - {at: 1.5 s, that: "MAIN.state = 1 AND Clamp.busy"}
  - {eventually: MAIN.cycleDone, within: 2.1 s}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, ForceHoldsAgainstTheWiringUntilReleased) {
  CaseResult held = run("set: {MAIN.start: TRUE}\ntime_limit: 2 s\nsteps:\n  - {at: 0 s, force: {MAIN.part: FALSE}}\nexpect:\n  - {never: Clamp.busy}\n");
  EXPECT_EQ(held.verdict, Verdict::Pass) << text(held);
  CaseResult released = run(
      "set: {MAIN.start: TRUE}\ntime_limit: 2 s\nsteps:\n  - {at: 0 s, force: {MAIN.part: FALSE}}\n  - {at: 0.5 s, release: all}\n"
      "expect:\n  - {never: Clamp.busy}\n");
  EXPECT_EQ(released.verdict, Verdict::Fail);
  EXPECT_NE(text(released).find("at 0.5 s: 'Clamp.busy' became true"), std::string::npos) << text(released);
}

TEST_F(ScenarioTest, WorldFactOffKeepsThePartSensorOff) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
time_limit: 2 s
steps:
  - {at: 0 s, facts: {partPresent: false}}
expect:
  - {always: "MAIN.state = 0 AND NOT PartSensor.value"}
  - {run_end: time_limit}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, SensorStuckAtZero) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
time_limit: 2 s
faults:
  - {device: PartSensor, stuck_output: 0}
expect:
  - {always: "MAIN.state = 0 AND world.partPresent"}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, DoneStuckFromAStepIsCaughtByTheWatchdog) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
time_limit: 5 s
steps:
  - {at: 0 s, fault: {device: Clamp, done_stuck: true}}
expect:
  - {fault_code: {variable: MAIN.lastError, code: 99}, within: 3.1 s}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

// A late done (the clamp's done 0.5 s after its 1 s close): the cycle ends 0.5 s later than the
// 1.03 s of the plain run, still inside the PLC's 3 s watchdog.
TEST_F(ScenarioTest, LateDoneFromAStepDelaysTheCycle) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
steps:
  - {at: 0 s, fault: {device: Clamp, extra_delay: 0.5 s}}
expect:
  - {cycle_time: {min: 1.5 s, max: 1.6 s}}
  - {never: MAIN.failed}
  - {at: 1.2 s, that: "MAIN.state = 1 AND NOT MAIN.done"}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

// An operator's push button: start pressed for 50 ms starts the cycle and is FALSE again after.
TEST_F(ScenarioTest, PressHoldsAButtonForItsDurationThenReleasesIt) {
  CaseResult r = run(R"(steps:
  - {at: 0.1 s, press: {MAIN.start: 50 ms}}
expect:
  - {at: 0.05 s, that: NOT MAIN.start AND MAIN.state = 0}
  - {at: 0.12 s, that: MAIN.start AND MAIN.state = 1}
  - {at: 0.15 s, that: NOT MAIN.start}
  - {eventually: MAIN.cycleDone, within: 1.2 s, from: 0.1 s}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
  r = run("steps:\n  - {at: 0.1 s, press: {MAIN.state: 50 ms, MAIN.start: fast}}\n");
  ASSERT_EQ(r.verdict, Verdict::Error);
  EXPECT_NE(text(r).find("test.yaml:3:25: error[C060]: 'MAIN.state' is INT: a pressed button is a BOOL"), std::string::npos) << text(r);
  EXPECT_NE(text(r).find("test.yaml:3:"), std::string::npos) << text(r);
}

TEST_F(ScenarioTest, ErrorAtTheSecondCommandOnly) {
  // The first command clamps, the second (the next part, at once) fails with the injected code.
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
cycles: 3
time_limit: 5 s
stop_on_device_error: false
faults:
  - {device: Clamp, error_code: 90, at_command: 2}
expect:
  - {in_order: ["MAIN.parts = 1", "MAIN.lastError = 90", MAIN.failed]}
  - {final: "MAIN.lastError = 90 AND MAIN.parts = 1"}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, PowerLossRestartsWarmWithRetainedVariables) {
  // parts (RETAIN) survives, start (not retained) does not: the second cycle needs a new start.
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
cycles: 2
steps:
  - {at: 2 s, power_loss: 0.5 s}
  - {at: 3 s, set: {MAIN.start: TRUE}}
expect:
  - {at: 1.5 s, that: "MAIN.parts = 1"}
  - {at: 2.2 s, that: "MAIN.parts = 0 AND NOT Clamp.busy"}
  - {at: 2.6 s, that: "MAIN.parts = 1 AND NOT MAIN.start AND MAIN.state = 0"}
  - {final: "MAIN.parts = 2"}
  - {run_end: completed}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

}  // namespace
}  // namespace virtcom::scenario::test
