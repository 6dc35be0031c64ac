// Every assertion kind of docs/scenarios.md, each with a case that holds and one that fails
// (with the failure's time and values), on the station cell: `start` is set before the first
// scan, the clamp closes from 0 to 1 s, the cycle ends at 1.03 s with MAIN.parts = 1.
#include <gtest/gtest.h>

#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

struct AssertionCase {
  const char* name;
  const char* expect;   // one entry of `expect:`
  bool holds;
  const char* message;  // a part of the failure message ("" when it holds)
};

const AssertionCase kCases[] = {
    {"AtHolds", "{at: 0.5 s, that: \"MAIN.state = 1 AND Clamp.busy\"}", true, ""},
    {"AtFails", "{at: 0.5 s, that: \"MAIN.state = 2\"}", false, "at 0.5 s: 'MAIN.state = 2' is false (MAIN.state = 1)"},
    {"EventuallyHolds", "{eventually: MAIN.cycleDone, within: 2 s}", true, ""},
    {"EventuallyFails", "{eventually: MAIN.cycleDone, within: 0.5 s}", false, "'MAIN.cycleDone' did not become true by 0.5 s (MAIN.cycleDone = FALSE)"},
    {"AlwaysHolds", "{always: NOT MAIN.failed}", true, ""},
    {"AlwaysFails", "{always: \"MAIN.state = 1\", from: 0.1 s}", false, "at 1.02 s: 'MAIN.state = 1' became false (MAIN.state = 2)"},
    {"NeverHolds", "{never: \"MAIN.state = 9\"}", true, ""},
    {"NeverFails", "{never: Clamp.busy, from: 0.2 s, to: 0.4 s}", false, "at 0.2 s: 'Clamp.busy' became true (Clamp.busy = TRUE)"},
    {"InOrderHolds", "{in_order: [Clamp.busy, MAIN.done, MAIN.cycleDone]}", true, ""},
    {"InOrderFails", "{in_order: [MAIN.cycleDone, Clamp.busy]}", false, "'Clamp.busy' became true before 'MAIN.cycleDone'"},
    {"CycleTimeHolds", "{cycle_time: {min: 1 s, max: 1.1 s}}", true, ""},
    {"CycleTimeFails", "{cycle_time: {max: 1 s}}", false, "at 1.03 s: cycle time 1.03 s > 1 s"},
    {"CycleTimeMinFails", "{cycle_time: {min: 1.5 s}}", false, "cycle time 1.03 s < 1.5 s"},
    {"EnergyHolds", "{energy: {device: Clamp, max: 150 J}}", true, ""},
    {"EnergyFails", "{energy: {max: 50 J}}", false, "energy 100 J > 50"},
    {"NoCollisionHolds", "{no_collision: true}", true, ""},
    {"PlcRunningHolds", "{plc_running: true}", true, ""},
    {"FaultCodeFails", "{fault_code: {variable: MAIN.lastError, code: 90}}", false, "'MAIN.lastError = 90' never became true"},
    {"FinalHolds", "{final: \"MAIN.parts = 1 AND MAIN.level > 0.4\"}", true, ""},
    {"FinalFails", "{final: \"MAIN.parts >= 2\"}", false, "at 1.03 s: 'MAIN.parts >= 2' is false at the end (MAIN.parts = 1)"},
    {"RunEndHolds", "{run_end: completed}", true, ""},
    {"RunEndFails", "{run_end: time_limit}", false, "the run ended: completed (1 cycle(s) completed)"},
};

class AssertionKinds : public ScenarioTest, public ::testing::WithParamInterface<AssertionCase> {};

TEST_P(AssertionKinds, HoldOrFailWithTimeAndValues) {
  const AssertionCase& c = GetParam();
  CaseResult r = run(std::string("set: {MAIN.start: TRUE}\nexpect:\n  - ") + c.expect + "\n");
  ASSERT_NE(r.verdict, Verdict::Error) << text(r);
  EXPECT_EQ(r.verdict, c.holds ? Verdict::Pass : Verdict::Fail) << text(r);
  if (!c.holds) {
    ASSERT_EQ(r.messages.size(), 1u);
    EXPECT_NE(r.messages[0].find(c.message), std::string::npos) << r.messages[0];
    EXPECT_NE(r.messages[0].find("test.yaml:4: "), std::string::npos) << "the assertion's file:line: " << r.messages[0];
  }
}

INSTANTIATE_TEST_SUITE_P(Scenario, AssertionKinds, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<AssertionCase>& info) { return std::string(info.param.name); });

TEST_F(ScenarioTest, FaultCodeSeenByThePlc) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
stop_on_device_error: false
time_limit: 3 s
faults:
  - {device: Clamp, error_code: 90, at_command: 1}
expect:
  - fault_code: {variable: MAIN.lastError, code: 90}
    within: 1 s
  - final: MAIN.state = 9 AND MAIN.failed
  - run_end: time_limit
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ScenarioTest, PlcRunningFailsDuringAPowerLoss) {
  CaseResult r = run(R"(steps:
  - {at: 0.3 s, power_loss: 0.2 s}
expect:
  - plc_running: true
)");
  EXPECT_EQ(r.verdict, Verdict::Fail);
  EXPECT_NE(text(r).find("at 0.3 s: the PLC is in STOP"), std::string::npos) << text(r);
}

TEST_F(ScenarioTest, ExpectedFailureIsNotASuiteFailureButAnUnexpectedPassIs) {
  CaseResult xfail = run("set: {MAIN.start: TRUE}\nxfail: the clamp is too slow\nexpect:\n  - cycle_time: {max: 0.5 s}\n");
  EXPECT_EQ(xfail.verdict, Verdict::ExpectedFail) << text(xfail);
  EXPECT_FALSE(verdictFails(xfail.verdict));
  CaseResult xpass = run("set: {MAIN.start: TRUE}\nxfail: the clamp is too slow\nexpect:\n  - cycle_time: {max: 5 s}\n");
  EXPECT_EQ(xpass.verdict, Verdict::UnexpectedPass);
  EXPECT_TRUE(verdictFails(xpass.verdict));
  EXPECT_NE(text(xpass).find("expected to fail (xfail: the clamp is too slow)"), std::string::npos);
}

TEST_F(ScenarioTest, ConditionsFollowPrecedenceAndReadFactsAndSignals) {
  CaseResult r = run(R"(set: {MAIN.start: TRUE}
expect:
  - at: 0.5 s
    that: NOT MAIN.failed AND MAIN.state = 2 OR world.partPresent AND PartSensor.value
  - at: 0.5 s
    that: NOT (MAIN.state = 1 XOR Clamp.busy) AND MAIN.level < 0.25 AND MAIN.cmd <> 0
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

}  // namespace
}  // namespace virtcom::scenario::test
