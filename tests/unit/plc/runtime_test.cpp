// The PLC runtime driven tick by tick on a virtual clock: RUN/STOP/FAULT, the watchdog, scan
// statistics, process images and determinism. Programs are compiled from ST text.
#include <gtest/gtest.h>

#include <algorithm>
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

// The value as `virtcom exec --print` shows it.
std::string valueOf(const Runtime& rt, const std::string& name) {
  auto ref = bc::resolveVariable(rt.module(), name);
  if (!ref) return "<unknown " + name + ">";
  return bc::formatValue(rt.module(), *ref, rt.machine().memory());
}

// Writes a value as `virtcom exec --set` does; the error text, empty on success.
std::string setValue(Runtime& rt, const std::string& name, const std::string& value) {
  auto ref = bc::resolveVariable(rt.module(), name);
  if (!ref) return "unknown " + name;
  return bc::writeValueFromText(rt.module(), *ref, value, rt.machine().memory());
}

const char* const kCounter = R"st(PROGRAM MAIN
VAR
  count : INT := 100;
END_VAR
count := count + 1;
END_PROGRAM
)st";

TEST(RuntimeState, ColdStartLoadsInitialValuesAndEntersRun) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  EXPECT_EQ(rt.state(), PlcState::Stop);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.state(), PlcState::Run);
  EXPECT_STREQ(stateName(rt.state()), "RUN");
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "100");
  EXPECT_EQ(rt.faultText(), "");
}

TEST(RuntimeState, EachTickRunsOneScanAndAdvancesTheClock) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.baseTickNs(), 10 * kMs);  // the default task
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(rt.nextTickNs(), k * 10 * kMs);
    ASSERT_TRUE(rt.tick());
    EXPECT_EQ(clock.nowNs(), k * 10 * kMs);  // scan k runs at k * interval
  }
  EXPECT_EQ(rt.ticks(), 3u);
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "103");
}

TEST(RuntimeState, StopSkipsScansButTimeGoesOnAndStartResumes) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  ASSERT_TRUE(rt.tick());
  rt.stop();
  EXPECT_EQ(rt.state(), PlcState::Stop);
  EXPECT_STREQ(stateName(rt.state()), "STOP");
  EXPECT_FALSE(rt.tick());
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "102");
  EXPECT_EQ(rt.stats(0).scans, 2u);
  EXPECT_EQ(clock.nowNs(), 30 * kMs);
  rt.start();
  EXPECT_EQ(rt.state(), PlcState::Run);
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(clock.nowNs(), 40 * kMs);
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "103");  // memory kept across STOP (warm resume)
  EXPECT_EQ(rt.stats(0).scans, 3u);
}

TEST(RuntimeState, TickBeforeColdStartRunsNothing) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(rt.stats(0).scans, 0u);
}

// Regression test (was a bug found by the e2e/unit suites).
TEST(RuntimeState, StartWithoutColdStartDoesNotRunAnUninitialisedImage) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  rt.start();  // cold-starts first: the initial value 100 is loaded
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "101");
}

TEST(RuntimeState, ColdStartAgainResetsToInitialValues) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  ASSERT_TRUE(rt.tick());
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(valueOf(rt, "MAIN.count"), "100");
  EXPECT_EQ(rt.ticks(), 0u);
}

// FB_exit (issue 16): once, at the end, in STOP afterwards; never before the first cold start
// or after a fault.
const char* const kExitCounter = R"st(VAR_GLOBAL
  gExits : INT;
  gDivisor : INT := 1;
END_VAR
FUNCTION_BLOCK FB_Closer
METHOD FB_exit : BOOL
gExits := gExits + 1 + 0 / gDivisor;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR
  closer : FB_Closer;
  q : INT;
END_VAR
q := 10 / gDivisor;
END_PROGRAM
)st";

TEST(RuntimeState, ExitCallsFbExitOnceAndStops) {
  auto module = compileSt(kExitCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  EXPECT_TRUE(rt.exit());  // never started: nothing to end
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(valueOf(rt, "gExits"), "0");
  ASSERT_TRUE(rt.tick());
  ASSERT_TRUE(rt.exit());
  EXPECT_EQ(valueOf(rt, "gExits"), "1");
  EXPECT_EQ(rt.state(), PlcState::Stop);
  EXPECT_TRUE(rt.exit());
  EXPECT_EQ(valueOf(rt, "gExits"), "1");
}

TEST(RuntimeState, NoFbExitAfterAFaultButAFaultInFbExitIsReported) {
  auto module = compileSt(kExitCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime faulted(*module, clock);
  ASSERT_TRUE(faulted.coldStart());
  ASSERT_EQ(setValue(faulted, "gDivisor", "0"), "");
  EXPECT_FALSE(faulted.tick());
  EXPECT_TRUE(faulted.exit());
  EXPECT_EQ(valueOf(faulted, "gExits"), "0");
  VirtualClock clock2;
  Runtime failing(*module, clock2);
  ASSERT_TRUE(failing.coldStart());
  ASSERT_EQ(setValue(failing, "gDivisor", "0"), "");
  EXPECT_FALSE(failing.exit());
  EXPECT_EQ(failing.state(), PlcState::Fault);
  EXPECT_NE(failing.faultText().find("division by zero at main.st:7:"), std::string::npos) << failing.faultText();
}

const char* const kDivByZero = R"st(PROGRAM MAIN
VAR
  divisor : INT := 3;
  q : INT;
END_VAR
divisor := divisor - 1;
q := 100 / divisor;
END_PROGRAM
)st";

TEST(RuntimeFault, DivisionByZeroFaultsInTheScanWhereItHappens) {
  auto module = compileSt(kDivByZero);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());  // 100 / 2
  ASSERT_TRUE(rt.tick());  // 100 / 1
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "100");
  EXPECT_FALSE(rt.tick());  // 100 / 0
  EXPECT_EQ(rt.state(), PlcState::Fault);
  EXPECT_STREQ(stateName(rt.state()), "FAULT");
  EXPECT_EQ(valueOf(rt, "MAIN.divisor"), "0");
  EXPECT_EQ(valueOf(rt, "MAIN.q"), "100");
  EXPECT_EQ(rt.stats(0).scans, 2u);  // the faulted scan is not counted
}

TEST(RuntimeFault, FaultTextNamesKindFileLineColumnAndTask) {
  auto module = compileSt(kDivByZero);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  while (rt.tick()) {
  }
  EXPECT_EQ(rt.faultText(), "division by zero at main.st:7:1 (task MainTask)");
}

TEST(RuntimeFault, FaultIsStickyUntilColdStart) {
  auto module = compileSt(kDivByZero);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  while (rt.tick()) {
  }
  ASSERT_EQ(rt.state(), PlcState::Fault);
  rt.start();
  EXPECT_EQ(rt.state(), PlcState::Fault);
  rt.stop();
  EXPECT_EQ(rt.state(), PlcState::Fault);
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.divisor"), "0");  // the program did not run again
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.state(), PlcState::Run);
  EXPECT_EQ(rt.faultText(), "");
  EXPECT_EQ(valueOf(rt, "MAIN.divisor"), "3");
  EXPECT_TRUE(rt.tick());
}

TEST(RuntimeFault, FaultInAFunctionShowsTheCallSite) {
  auto module = compileSt(R"st(FUNCTION Ratio : INT
VAR_INPUT a, b : INT; END_VAR
Ratio := a / b;
END_FUNCTION

PROGRAM MAIN
VAR
  r : INT;
  zero : INT;
END_VAR
r := Ratio(10, zero);
END_PROGRAM
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(rt.faultText(),
            "division by zero at main.st:3:1\n"
            "  called from main.st:11:1 (in MAIN) (task MainTask)");
}

// Regression test (was a bug found by the e2e/unit suites).
TEST(StandardNames, UserFunctionNamedLikeAStandardFunctionIsNotSilentlyIgnored) {
  const char* text = R"st(FUNCTION Div : INT
VAR_INPUT a, b : INT; END_VAR
Div := 42;
END_FUNCTION

PROGRAM MAIN
VAR
  r : INT;
END_VAR
r := Div(10, 2);
END_PROGRAM
)st";
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", text}}, sources, diags);
  if (!module) {
    EXPECT_NE(diags.render(sources).find("error[E119]"), std::string::npos) << diags.render(sources);
    return;
  }
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.r"), "42");
}

const char* const kEndless = R"st(PROGRAM MAIN
VAR
  x : DINT;
END_VAR
WHILE TRUE DO
  x := x + 1;
END_WHILE;
END_PROGRAM
)st";

TEST(RuntimeWatchdog, EndlessLoopFaultsInsteadOfHanging) {
  auto module = compileSt(kEndless);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  RuntimeOptions options;
  options.instructionBudget = 10'000;
  Runtime rt(*module, clock, options);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(rt.state(), PlcState::Fault);
  EXPECT_TRUE(rt.faultText().starts_with("watchdog: instruction budget exhausted at main.st:")) << rt.faultText();
  EXPECT_TRUE(rt.faultText().ends_with("(task MainTask)")) << rt.faultText();
  // It ran (about) as many iterations as the budget allows, then stopped.
  EXPECT_NE(valueOf(rt, "MAIN.x"), "0");
}

TEST(RuntimeWatchdog, BudgetIsPerScanNotCumulative) {
  auto module = compileSt(R"st(PROGRAM MAIN
VAR
  i : INT;
  total : DINT;
END_VAR
FOR i := 1 TO 100 DO
  total := total + 1;
END_FOR;
END_PROGRAM
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  RuntimeOptions options;
  options.instructionBudget = 1'000;  // ~100 backward jumps per scan fit; 50 scans would not
  Runtime rt(*module, clock, options);
  ASSERT_TRUE(rt.coldStart());
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(rt.tick()) << "scan " << k << ": " << rt.faultText();
  EXPECT_EQ(valueOf(rt, "MAIN.total"), "5000");
}

TEST(RuntimeStats, CountsScansPerTaskAndOrdersExecTimes) {
  auto module = compileSt(kCounter);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(rt.stats(0).scans, 0u);
  EXPECT_EQ(rt.stats(0).avgExecNs(), 0);
  for (int k = 0; k < 25; ++k) ASSERT_TRUE(rt.tick());
  const TaskStats& s = rt.stats(0);
  EXPECT_EQ(s.scans, 25u);
  EXPECT_GE(s.minExecNs, 0);
  EXPECT_LE(s.minExecNs, s.avgExecNs());
  EXPECT_LE(s.avgExecNs(), s.maxExecNs);
  EXPECT_GE(s.totalExecNs, s.maxExecNs);
}

const char* const kImages = R"st(PROGRAM MAIN
VAR
  x AT %IX0.0 : BOOL;
  x3 AT %IX0.3 : BOOL;
  level AT %IW2 : INT;
  seen : BOOL;
  seenLevel : INT;
  w AT %QW0 : WORD := 16#1234;
  q AT %QX2.1 : BOOL;
END_VAR
seen := x;
seenLevel := level;
w := w + 1;
q := x3;
END_PROGRAM
)st";

TEST(ProcessImage, InputsAreCopiedInOnlyAtTheStartOfAScan) {
  auto module = compileSt(kImages);
  ASSERT_NE(module, nullptr);
  ASSERT_GE(module->inputs.size, 6u);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  rt.inputImage()[0] = 0x01;
  EXPECT_EQ(valueOf(rt, "MAIN.x"), "FALSE");  // written by a device, not yet sampled
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.x"), "TRUE");
  EXPECT_EQ(valueOf(rt, "MAIN.seen"), "TRUE");
  EXPECT_EQ(valueOf(rt, "MAIN.x3"), "FALSE");
  rt.inputImage()[0] = 0x08;  // %IX0.0 off, %IX0.3 on
  EXPECT_EQ(valueOf(rt, "MAIN.x"), "TRUE");
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.x"), "FALSE");
  EXPECT_EQ(valueOf(rt, "MAIN.seen"), "FALSE");
  EXPECT_EQ(valueOf(rt, "MAIN.x3"), "TRUE");
}

TEST(ProcessImage, InputWordIsNumberedInWordsAndLittleEndian) {
  auto module = compileSt(kImages);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  rt.inputImage()[2] = 0xff;  // bytes 2..3 are %IW1, not %IW2
  rt.inputImage()[3] = 0xff;
  rt.inputImage()[4] = 0x2c;  // CODESYS numbering: %IW2 starts at byte 4; 300 = 16#012C
  rt.inputImage()[5] = 0x01;
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.seenLevel"), "300");
}

TEST(ProcessImage, WritesIntoTheInputAreaAreOverwrittenByTheNextSample) {
  auto module = compileSt(kImages);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  ASSERT_EQ(setValue(rt, "MAIN.x", "TRUE"), "");  // memory, not the input image
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.seen"), "FALSE");  // the device says FALSE
}

TEST(ProcessImage, OutputsArePublishedOnlyAtTheEndOfAScan) {
  auto module = compileSt(kImages);
  ASSERT_NE(module, nullptr);
  ASSERT_GE(module->outputs.size, 3u);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  EXPECT_EQ(valueOf(rt, "MAIN.w"), "4660");  // 16#1234 in memory...
  EXPECT_EQ(rt.outputImage()[0], 0x00);      // ...but no scan has published it yet
  EXPECT_EQ(rt.outputImage()[1], 0x00);
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(rt.outputImage()[0], 0x35);  // 16#1235, little-endian
  EXPECT_EQ(rt.outputImage()[1], 0x12);
  ASSERT_EQ(setValue(rt, "MAIN.w", "7"), "");  // between scans: not published
  EXPECT_EQ(rt.outputImage()[0], 0x35);
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(rt.outputImage()[0], 0x08);
  EXPECT_EQ(rt.outputImage()[1], 0x00);
}

TEST(ProcessImage, OutputBitLandsInItsByteAndBit) {
  auto module = compileSt(kImages);
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  rt.inputImage()[0] = 0x08;  // x3 -> q
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(rt.outputImage()[2], 0x02);  // %QX2.1
  rt.inputImage()[0] = 0x00;
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(rt.outputImage()[2], 0x00);
}

TEST(ProcessImage, OutputsKeepTheirLastValueAfterAFault) {
  auto module = compileSt(R"st(PROGRAM MAIN
VAR
  out AT %QB0 : BYTE;
  d : INT := 2;
  r : INT;
END_VAR
out := out + 1;
d := d - 1;
r := 10 / d;
END_PROGRAM
)st");
  ASSERT_NE(module, nullptr);
  VirtualClock clock;
  Runtime rt(*module, clock);
  ASSERT_TRUE(rt.coldStart());
  ASSERT_TRUE(rt.tick());
  EXPECT_EQ(rt.outputImage()[0], 1);
  EXPECT_FALSE(rt.tick());
  EXPECT_EQ(valueOf(rt, "MAIN.out"), "2");  // memory was written before the fault...
  EXPECT_EQ(rt.outputImage()[0], 1);        // ...but a faulted scan publishes nothing
}

// A program that exercises integer wrap-around, LREAL math, strings, arrays and a timer.
const char* const kBusy = R"st(PROGRAM MAIN
VAR
  seed : UDINT := 12345;
  acc : LREAL;
  r : REAL;
  t : TON;
  k : INT;
  arr : ARRAY[0..15] OF DINT;
  s : STRING := 'x';
END_VAR
seed := seed * 1103515245 + 12345;
acc := acc + UDINT_TO_LREAL(seed MOD 1000) / 7.0;
r := LREAL_TO_REAL(SIN(acc));
t(IN := (k MOD 20) < 15, PT := T#70ms);
arr[k MOD 16] := arr[k MOD 16] + UDINT_TO_DINT(seed MOD 100);
IF t.Q THEN
  s := CONCAT(RIGHT(s, 5), 'y');
END_IF;
k := k + 1;
END_PROGRAM
)st";

TEST(RuntimeDeterminism, SameModuleTwoRuntimesGiveIdenticalMemory) {
  auto module = compileSt(kBusy);
  ASSERT_NE(module, nullptr);
  VirtualClock clockA, clockB;
  Runtime a(*module, clockA), b(*module, clockB);
  ASSERT_TRUE(a.coldStart());
  ASSERT_TRUE(b.coldStart());
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(a.tick()) << a.faultText();
    ASSERT_TRUE(b.tick()) << b.faultText();
  }
  ASSERT_EQ(a.machine().memorySize(), b.machine().memorySize());
  EXPECT_TRUE(std::equal(a.machine().memory(), a.machine().memory() + a.machine().memorySize(),
                         b.machine().memory()));
  EXPECT_EQ(valueOf(a, "MAIN.k"), "200");
  EXPECT_NE(valueOf(a, "MAIN.s"), "'x'");  // the timer fired: the test exercised the string path
}

TEST(RuntimeDeterminism, TwoCompilationsGiveIdenticalImagesAndRuns) {
  auto m1 = compileSt(kBusy);
  auto m2 = compileSt(kBusy);
  ASSERT_NE(m1, nullptr);
  ASSERT_NE(m2, nullptr);
  EXPECT_EQ(m1->initialImage, m2->initialImage);
  VirtualClock clockA, clockB;
  Runtime a(*m1, clockA), b(*m2, clockB);
  ASSERT_TRUE(a.coldStart());
  ASSERT_TRUE(b.coldStart());
  for (int k = 0; k < 100; ++k) {
    ASSERT_TRUE(a.tick());
    ASSERT_TRUE(b.tick());
  }
  ASSERT_EQ(a.machine().memorySize(), b.machine().memorySize());
  EXPECT_TRUE(std::equal(a.machine().memory(), a.machine().memory() + a.machine().memorySize(),
                         b.machine().memory()));
}

TEST(RuntimeDeterminism, ResultDoesNotDependOnHowFastTheHostRuns) {
  // Interleaving other work between ticks (here: another runtime) changes nothing.
  auto module = compileSt(kBusy);
  ASSERT_NE(module, nullptr);
  VirtualClock clockA, clockB, clockC;
  Runtime a(*module, clockA), b(*module, clockB), noise(*module, clockC);
  ASSERT_TRUE(a.coldStart());
  ASSERT_TRUE(b.coldStart());
  ASSERT_TRUE(noise.coldStart());
  for (int k = 0; k < 60; ++k) ASSERT_TRUE(a.tick());
  for (int k = 0; k < 60; ++k) {
    for (int n = 0; n < k % 4; ++n) ASSERT_TRUE(noise.tick());
    ASSERT_TRUE(b.tick());
  }
  EXPECT_TRUE(std::equal(a.machine().memory(), a.machine().memory() + a.machine().memorySize(),
                         b.machine().memory()));
}

}  // namespace
}  // namespace virtcom::plc
