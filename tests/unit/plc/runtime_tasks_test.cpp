// Tasks configured in ST (CONFIGURATION / RESOURCE / TASK): the base tick, each program at its
// own rate, priorities, and the task time that timers see.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace virtcom::plc {
namespace {

constexpr int64_t kMs = 1'000'000;

std::unique_ptr<bc::Module> compileSt(const std::string& text) {
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", text}}, sources, diags);
  EXPECT_NE(module, nullptr) << diags.render(sources);
  return module;
}

std::string compileErrors(const std::string& text) {
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", text}}, sources, diags);
  EXPECT_EQ(module, nullptr);
  return diags.render(sources);
}

std::string valueOf(const Runtime& rt, const std::string& name) {
  auto ref = bc::resolveVariable(rt.module(), name);
  if (!ref) return "<unknown " + name + ">";
  return bc::formatValue(rt.module(), *ref, rt.machine().memory());
}

// Each program counts its runs and keeps the elapsed time of a timer started in its first scan.
const char* const kTwoPrograms = R"st(
PROGRAM P1
VAR runs : INT; t : TON; et : TIME; END_VAR
runs := runs + 1;
t(IN := TRUE, PT := T#1h);
et := t.ET;
END_PROGRAM

PROGRAM P2
VAR runs : INT; t : TON; et : TIME; END_VAR
runs := runs + 1;
t(IN := TRUE, PT := T#1h);
et := t.ET;
END_PROGRAM
)st";

std::string twoTasks(const std::string& fast, const std::string& slow) {
  return std::string(kTwoPrograms) + "CONFIGURATION Cell\n  RESOURCE Cpu ON PLC\n" +
         "    TASK fast(INTERVAL := " + fast + ", PRIORITY := 1);\n" +
         "    TASK slow(INTERVAL := " + slow + ", PRIORITY := 2);\n" +
         "    PROGRAM p1 WITH fast : P1;\n    PROGRAM p2 WITH slow : P2;\n  END_RESOURCE\nEND_CONFIGURATION\n";
}

TEST(RuntimeTasks, ConfiguredTasksAreInTheModule) {
  auto module = compileSt(twoTasks("T#10ms", "T#30ms"));
  ASSERT_NE(module, nullptr);
  ASSERT_EQ(module->tasks.size(), 2u);
  EXPECT_EQ(module->tasks[0].name, "fast");
  EXPECT_EQ(module->tasks[0].intervalNs, 10 * kMs);
  EXPECT_EQ(module->tasks[0].priority, 1);
  EXPECT_EQ(module->tasks[1].name, "slow");
  EXPECT_EQ(module->tasks[1].intervalNs, 30 * kMs);
  EXPECT_EQ(module->tasks[1].priority, 2);
  EXPECT_FALSE(module->tasks[0].isDefault) << "declared by a TASK";
  EXPECT_FALSE(module->tasks[1].isDefault) << "declared by a TASK";
}

TEST(RuntimeTasks, EachProgramRunsAtItsOwnRate) {
  auto module = compileSt(twoTasks("T#10ms", "T#30ms"));
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.baseTickNs(), 10 * kMs);
  for (int k = 0; k < 7; ++k) ASSERT_TRUE(rt.tick());  // 0, 10, ..., 60 ms
  EXPECT_EQ(valueOf(rt, "p1.runs"), "7");
  EXPECT_EQ(valueOf(rt, "p2.runs"), "3");  // 0, 30, 60 ms
  EXPECT_EQ(rt.stats(0).scans, 7u);
  EXPECT_EQ(rt.stats(1).scans, 3u);
}

TEST(RuntimeTasks, BaseTickIsTheGcdOfTheIntervals) {
  auto module = compileSt(twoTasks("T#20ms", "T#30ms"));
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.baseTickNs(), 10 * kMs);
  ASSERT_TRUE(rt.tick());  // 0 ms: both
  ASSERT_TRUE(rt.tick());  // 10 ms: neither is due, still a successful tick
  EXPECT_EQ(valueOf(rt, "p1.runs"), "1");
  EXPECT_EQ(valueOf(rt, "p2.runs"), "1");
  for (int k = 2; k < 7; ++k) ASSERT_TRUE(rt.tick());  // ... 60 ms
  EXPECT_EQ(valueOf(rt, "p1.runs"), "4");  // 0, 20, 40, 60
  EXPECT_EQ(valueOf(rt, "p2.runs"), "3");  // 0, 30, 60
  EXPECT_EQ(rt.ticks(), 7u);
  EXPECT_EQ(clock.nowNs(), 60 * kMs);
}

TEST(RuntimeTasks, LtimeIntervalsBelowAMillisecond) {
  auto module = compileSt(twoTasks("LTIME#1500us", "T#1ms"));
  ASSERT_NE(module, nullptr);
  EXPECT_EQ(module->tasks[0].intervalNs, 1'500'000);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.baseTickNs(), 500'000);
  for (int k = 0; k < 7; ++k) ASSERT_TRUE(rt.tick());  // 0 .. 3 ms in 0.5 ms steps
  EXPECT_EQ(valueOf(rt, "p1.runs"), "3");  // 0, 1.5, 3 ms
  EXPECT_EQ(valueOf(rt, "p2.runs"), "4");  // 0, 1, 2, 3 ms
}

TEST(RuntimeTasks, TimersSeeTheTickTimeOfTheirTask) {
  auto module = compileSt(twoTasks("T#10ms", "T#30ms"));
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  for (int k = 0; k < 7; ++k) ASSERT_TRUE(rt.tick());
  EXPECT_EQ(clock.nowNs(), 60 * kMs);
  EXPECT_EQ(valueOf(rt, "p1.et"), "T#60ms");
  EXPECT_EQ(valueOf(rt, "p2.et"), "T#60ms");
  ASSERT_TRUE(rt.tick());  // 70 ms: only the fast task runs
  EXPECT_EQ(valueOf(rt, "p1.et"), "T#70ms");
  EXPECT_EQ(valueOf(rt, "p2.et"), "T#60ms");
}

TEST(RuntimeTasks, TimeBetweenScansOfTheDefaultTaskIsTheCycleTime) {
  auto module = compileSt(R"st(PROGRAM MAIN
VAR t : TON; q : BOOL; et : TIME; END_VAR
t(IN := TRUE, PT := T#50ms);
q := t.Q;
et := t.ET;
END_PROGRAM
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(rt.tick());  // 0 .. 40 ms
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "FALSE");
  EXPECT_EQ(valueOf(rt, "MAIN.et"), "T#40ms");
  ASSERT_TRUE(rt.tick());  // 50 ms
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "TRUE");
  EXPECT_EQ(valueOf(rt, "MAIN.et"), "T#50ms");
}

TEST(RuntimeTasks, ChangingTheDefaultTaskIntervalChangesTimerTiming) {
  auto module = compileSt(R"st(PROGRAM MAIN
VAR t : TON; q : BOOL; END_VAR
t(IN := TRUE, PT := T#100ms);
q := t.Q;
END_PROGRAM
)st");
  ASSERT_NE(module, nullptr);
  ASSERT_EQ(module->tasks.size(), 1u);
  EXPECT_EQ(module->tasks[0].name, "MainTask");
  EXPECT_TRUE(module->tasks[0].isDefault) << "the compiler's task of a program without CONFIGURATION";
  module->tasks[0].intervalNs = 50 * kMs;  // what `exec --cycle-time 50ms` does
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.baseTickNs(), 50 * kMs);
  ASSERT_TRUE(rt.tick());  // 0
  ASSERT_TRUE(rt.tick());  // 50
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "FALSE");
  ASSERT_TRUE(rt.tick());  // 100
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "TRUE");
}

TEST(RuntimeTasks, LowerPriorityNumberRunsFirstWhenBothAreDue) {
  auto module = compileSt(R"st(
PROGRAM PLow
seq := seq + 1;
lowAt := seq;
END_PROGRAM

PROGRAM PHigh
seq := seq + 1;
highAt := seq;
END_PROGRAM

CONFIGURATION Cell
  VAR_GLOBAL
    seq : INT;
    lowAt : INT;
    highAt : INT;
  END_VAR
  RESOURCE Cpu ON PLC
    TASK low(INTERVAL := T#10ms, PRIORITY := 5);
    TASK high(INTERVAL := T#20ms, PRIORITY := 1);
    PROGRAM l WITH low : PLow;
    PROGRAM h WITH high : PHigh;
  END_RESOURCE
END_CONFIGURATION
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());  // 0 ms: both due, high first
  EXPECT_EQ(valueOf(rt, "highAt"), "1");
  EXPECT_EQ(valueOf(rt, "lowAt"), "2");
  ASSERT_TRUE(rt.tick());  // 10 ms: low only
  EXPECT_EQ(valueOf(rt, "lowAt"), "3");
  EXPECT_EQ(valueOf(rt, "highAt"), "1");
  ASSERT_TRUE(rt.tick());  // 20 ms: both, high first
  EXPECT_EQ(valueOf(rt, "highAt"), "4");
  EXPECT_EQ(valueOf(rt, "lowAt"), "5");
}

TEST(RuntimeTasks, ProgramsOfOneTaskRunInDeclarationOrder) {
  auto module = compileSt(R"st(
PROGRAM PA
seq := seq * 10 + 1;
END_PROGRAM

PROGRAM PB
seq := seq * 10 + 2;
END_PROGRAM

CONFIGURATION Cell
  VAR_GLOBAL seq : DINT; END_VAR
  RESOURCE Cpu ON PLC
    TASK only(INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM b WITH only : PB;
    PROGRAM a WITH only : PA;
  END_RESOURCE
END_CONFIGURATION
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "seq"), "2121");
}

TEST(RuntimeTasks, ProgramWithoutWithRunsInTheDefaultTask) {
  auto module = compileSt(std::string(kTwoPrograms) + R"st(
CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK slow(INTERVAL := T#30ms, PRIORITY := 2);
    PROGRAM p1 : P1;
    PROGRAM p2 WITH slow : P2;
  END_RESOURCE
END_CONFIGURATION
)st");
  ASSERT_NE(module, nullptr);
  ASSERT_EQ(module->tasks.size(), 2u);
  EXPECT_EQ(module->tasks[0].name, "__DEFAULT");
  EXPECT_TRUE(module->tasks[0].isDefault) << "the compiler's task of a configured program without WITH";
  EXPECT_FALSE(module->tasks[1].isDefault);
  EXPECT_EQ(module->tasks[0].intervalNs, 10 * kMs);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "p1.runs"), "4");
  EXPECT_EQ(valueOf(rt, "p2.runs"), "2");
}

TEST(RuntimeTasks, FaultTextNamesTheConfiguredTask) {
  auto module = compileSt(R"st(
PROGRAM PBad
VAR d : INT; r : INT; END_VAR
r := 1 / d;
END_PROGRAM

CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK fast(INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM bad WITH fast : PBad;
  END_RESOURCE
END_CONFIGURATION
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(rt.faultText(), "division by zero at main.st:4:1 (task fast)");
}

TEST(RuntimeTasks, InvalidTaskConfigurationIsACompileError) {
  std::string out = compileErrors(std::string(kTwoPrograms) + R"st(
CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK fast(INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM p1 WITH nosuch : P1;
  END_RESOURCE
END_CONFIGURATION
)st");
  EXPECT_NE(out.find("error[E118]: unknown TASK 'nosuch'"), std::string::npos) << out;
}

}  // namespace
}  // namespace virtcom::plc
