// Scenarios of a PLC program alone (`program:` instead of `cell:`, docs/scenarios.md): stimuli and
// assertions on the program's variables pass and fail as with a cell, the task's cycle time comes
// from `cycle_time:`, and every key about devices, their world or the cell's cycle is refused at
// its position with the reason.
#include <gtest/gtest.h>

#include <fstream>

#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

const char* kProgram = R"(PROGRAM MAIN
VAR
  start : BOOL;
  count : INT;
  done : BOOL;
  t : TON;
END_VAR
IF start THEN
  count := count + 1;
END_IF
t(IN := start, PT := T#500ms);
done := t.Q;
END_PROGRAM
)";

class ProgramAlone : public ScenarioTest {
 protected:
  // Writes prog.st and `scenario` (the whole file) as test.yaml and runs it.
  CaseResult runProgram(const std::string& scenario) {
    std::ofstream(dir_ / "prog.st") << kProgram;
    const std::string path = (dir_ / "test.yaml").string();
    std::ofstream(path) << scenario;
    return runCase(CaseSpec{path, SIZE_MAX, "test", "test"}, {});
  }
};

TEST_F(ProgramAlone, StimuliAndAssertionsOnItsVariablesPass) {
  CaseResult r = runProgram(R"(program: prog.st
time_limit: 2 s
steps:
  - {at: 0.2 s, set: {MAIN.start: TRUE}}
expect:
  - {at: 0.1 s, that: NOT MAIN.start}
  - {eventually: MAIN.done, from: 0.2 s, within: 0.6 s}
  - {never: MAIN.done, to: 0.65 s}
  - {in_order: [MAIN.start, MAIN.done]}
  - {final: "MAIN.count > 150"}
  - {plc_running: true}
  - {run_end: time_limit}
)");
  EXPECT_EQ(r.verdict, Verdict::Pass) << text(r);
}

TEST_F(ProgramAlone, AFailedAssertionSaysWhenAndWhatTheValuesWere) {
  CaseResult r = runProgram(R"(program: [prog.st]
time_limit: 1 s
set: {MAIN.start: TRUE}
expect:
  - {at: 0.4 s, that: MAIN.done}
)");
  EXPECT_EQ(r.verdict, Verdict::Fail);
  EXPECT_NE(text(r).find("test.yaml:5: at 0.4 s that MAIN.done: at 0.4 s: 'MAIN.done' is false (MAIN.done = FALSE)"), std::string::npos)
      << text(r);
}

TEST_F(ProgramAlone, CycleTimeSetsTheTask) {
  CaseResult fast = runProgram(R"(program: {sources: [prog.st], cycle_time: 1 ms}
time_limit: 1 s
set: {MAIN.start: TRUE}
expect:
  - {final: "MAIN.count >= 1000"}
)");
  EXPECT_EQ(fast.verdict, Verdict::Pass) << text(fast);
  CaseResult plain = runProgram(R"(program: prog.st
time_limit: 1 s
set: {MAIN.start: TRUE}
expect:
  - {final: "MAIN.count <= 101"}
)");
  EXPECT_EQ(plain.verdict, Verdict::Pass) << text(plain);  // 10 ms, the default task
}

struct Refusal {
  const char* name;
  const char* scenario;
  const char* diagnostic;
};

const Refusal kRefusals[] = {
    {"CellAndProgram", "cell: ../cell.yaml\nprogram: prog.st\n",
     "test.yaml:2:1: error[C060]: a scenario runs either a cell ('cell:') or a PLC program alone ('program:'), not both"},
    {"Neither", "name: nothing to run\nexpect:\n  - {final: MAIN.done}\n",
     "test.yaml:1:1: error[C060]: a scenario names the cell it runs ('cell: ../cell.yaml') or a PLC program alone ('program: main.st')"},
    {"NoCollision", "program: prog.st\nexpect:\n  - {no_collision: true}\n",
     "test.yaml:3:6: error[C010]: 'no_collision' needs a cell (devices, their world, its cycle): this scenario runs a PLC program alone ('program:')"},
    {"Energy", "program: prog.st\nexpect:\n  - {energy: {max: 10 J}}\n", "test.yaml:3:6: error[C010]: 'energy' needs a cell"},
    {"CycleTime", "program: prog.st\nexpect:\n  - {cycle_time: {max: 10 s}}\n", "test.yaml:3:6: error[C010]: 'cycle_time' needs a cell"},
    {"DeviceFaults", "program: prog.st\nfaults:\n  - {device: Press, error_code: 90}\n", "test.yaml:2:1: error[C010]: 'faults' needs a cell"},
    {"Cycles", "program: prog.st\ncycles: 2\n", "test.yaml:2:1: error[C010]: 'cycles' needs a cell"},
    {"StopOnCollision", "program: prog.st\nstop_on_collision: false\n", "test.yaml:2:1: error[C010]: 'stop_on_collision' needs a cell"},
    {"Facts", "program: prog.st\nsteps:\n  - {at: 1 s, facts: {stud1: false}}\n", "test.yaml:3:15: error[C010]: 'facts' needs a cell"},
    {"StepFault", "program: prog.st\nsteps:\n  - {at: 1 s, fault: {device: Press, done_stuck: true}}\n",
     "test.yaml:3:15: error[C010]: 'fault' needs a cell"},
    {"Parameter", "program: prog.st\nsteps:\n  - {at: 1 s, parameter: {Press.time: 2 s}}\n",
     "test.yaml:3:15: error[C010]: 'parameter' needs a cell"},
    {"UnknownProgramKey", "program: {sources: [prog.st], cycle: 1 ms}\n", "test.yaml:1:31: error[C011]: unknown key 'cycle' in 'program'"},
    {"NoSources", "program: {cycle_time: 1 ms}\n", "test.yaml:1:10: error[C010]: 'program' names its 'sources'"},
    {"MissingFile", "program: nosuch.st\n", "test.yaml:1:10: error[C010]: cannot read PLC source"},
};

class ProgramAloneRefusals : public ProgramAlone, public ::testing::WithParamInterface<Refusal> {};

TEST_P(ProgramAloneRefusals, ReportedAtTheKey) {
  CaseResult r = runProgram(GetParam().scenario);
  ASSERT_EQ(r.verdict, Verdict::Error) << text(r);
  EXPECT_TRUE(firstDiagnostic(r).starts_with(GetParam().diagnostic)) << firstDiagnostic(r);
}

INSTANTIATE_TEST_SUITE_P(Scenario, ProgramAloneRefusals, ::testing::ValuesIn(kRefusals),
                         [](const ::testing::TestParamInfo<Refusal>& info) { return std::string(info.param.name); });

TEST_F(ProgramAlone, ACompileErrorIsReportedInTheProgram) {
  std::ofstream(dir_ / "bad.st") << "PROGRAM MAIN\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n";
  const std::string path = (dir_ / "test.yaml").string();
  std::ofstream(path) << "program: bad.st\n";
  CaseResult r = runCase(CaseSpec{path, SIZE_MAX, "test", "test"}, {});
  ASSERT_EQ(r.verdict, Verdict::Error);
  EXPECT_TRUE(firstDiagnostic(r).starts_with("bad.st:3:6: error[")) << firstDiagnostic(r);
}

}  // namespace
}  // namespace virtcom::scenario::test
