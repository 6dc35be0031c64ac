// The AOT backend against the interpreter on random bytecode (every opcode, faults, calls,
// natives), on a compiled ST program with a nested fault, and its fallbacks and cache.
// The golden programs are compared in tests/golden (Golden.AotMatchesInterpreter).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <random>

#include "../vm/random_instr.hpp"
#include "../vm/test_module_builder.hpp"
#include "aot/c_source.hpp"
#include "aot/compile.hpp"
#include "aot/module_key.hpp"
#include "aot/register_plan.hpp"
#include "bytecode/verifier.hpp"
#include "lang/st/compiler.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

namespace fs = std::filesystem;
using bc::Op;

aot::CompileOptions testOptions() {
  aot::CompileOptions o;
  o.cacheDir = VIRTCOM_AOT_TEST_CACHE;
  return o;
}

// A verified module of `count` random POUs: each POU is drawn until the module still verifies
// with it, so calls go to any POU before it or to itself. Each POU first loads its registers
// from r2 up, as compiled ST does: a register read before any write holds whatever the last
// user of that register-stack slot left there, which the AOT code does not promise to match
// (src/aot/README.md).
bc::Module randomModule(std::mt19937& rng, uint32_t count) {
  test::ModuleBuilder b = test::randomModuleTables(rng);
  while (b.m.pous.size() < count) {
    const bc::Module before = b.m;
    const auto regs = static_cast<uint16_t>(2 + rng() % 10);
    const uint32_t size = 2 + rng() % 12;
    const auto pous = static_cast<uint32_t>(b.m.pous.size() + 1);
    b.beginPou("P" + std::to_string(pous - 1), regs, rng() % 64, 16 + rng() % 128);
    const uint32_t start = b.pc();
    for (uint16_t r = 2; r < regs; ++r) b.emit(test::abx(Op::LDI, r, rng() % 600));
    for (uint32_t i = 0; i + 1 < size; ++i)
      b.emit(test::randomInstr(rng, regs, b.pc(), start, regs - 2 + size, pous), 1 + i);
    b.emit(rng() % 8 ? bc::Instr::abc(Op::RET, 0, 0, 0)
                     : test::randomInstr(rng, regs, b.pc(), start, regs - 2 + size, pous));
    if (!bc::verifyModule(b.m).empty()) b.m = before;
  }
  return b.m;
}

// Runs one POU on both machines and expects the same outcome, fault report, memory image,
// stack pointer and time reads. `faulted` counts the faults.
void expectSameRun(vm::Machine& interp, vm::Machine& compiled, const bc::Module& m, uint32_t pou, uint32_t self,
                   int64_t now, int& faulted) {
  interp.setTaskTimeNs(now);
  compiled.setTaskTimeNs(now);
  const bool ok = interp.run(pou, self);
  faulted += !ok;
  ASSERT_EQ(compiled.run(pou, self), ok) << "P" << pou << ": " << interp.fault().describe(m);
  if (!ok) {
    EXPECT_EQ(compiled.fault().describe(m), interp.fault().describe(m));
    EXPECT_EQ(compiled.fault().kind, interp.fault().kind);
  }
  EXPECT_EQ(compiled.stackPointer(), interp.stackPointer());
  EXPECT_EQ(compiled.timeReads(), interp.timeReads());
  const uint8_t* a = interp.memory();
  const auto diff = std::mismatch(a, a + interp.memorySize(), compiled.memory());
  ASSERT_EQ(diff.first, a + interp.memorySize()) << "P" << pou << " memory differs at " << (diff.first - a);
}

// Split into units of about 200 instructions (some 15 units), so that calls also cross units
// and recursion runs through the exported functions; the other tests cover single units.
TEST(Aot, RandomBytecodeRunsAsOnTheInterpreter) {
  std::mt19937 rng(20261201);
  const bc::Module m = randomModule(rng, 200);
  aot::CompileOptions options = testOptions();
  options.unitInstructions = 200;
  const aot::CompileResult compiled = aot::compileModule(m, options);
  ASSERT_TRUE(compiled.code) << compiled.error;
  EXPECT_GT(compiled.units, 5u);
  vm::Machine interp(m), native(m);
  native.useCompiled(compiled.code);
  for (vm::Machine* vm : {&interp, &native}) {
    vm->setBudget(200);
    ASSERT_TRUE(vm->coldStart());
  }
  int faults = 0;
  for (int round = 0; round < 2000; ++round) {
    const auto pou = static_cast<uint32_t>(rng() % m.pous.size());
    ASSERT_NO_FATAL_FAILURE(expectSameRun(interp, native, m, pou, static_cast<uint32_t>(rng() % 300), round * 1'000'000, faults));
  }
  EXPECT_GT(faults, 100);  // the comparison covered faults, not only clean runs
  EXPECT_LT(faults, 1900);
}

// An ST program compiled once, with an interpreter and an AOT machine on it, both cold-started.
struct BothBackends {
  std::unique_ptr<bc::Module> m;
  std::unique_ptr<vm::Machine> interp, native;
};

void prepare(const std::string& source, BothBackends& b, uint64_t budget = 50'000'000,
             const aot::CompileOptions& options = testOptions(), aot::CompileResult* result = nullptr) {
  SourceManager sources;
  Diagnostics diags;
  b.m = st::compileProgram({{"main.st", source}}, sources, diags);
  ASSERT_NE(b.m, nullptr) << diags.render(sources);
  const aot::CompileResult compiled = aot::compileModule(*b.m, options);
  ASSERT_TRUE(compiled.code) << compiled.error;
  if (result) *result = compiled;
  b.interp = std::make_unique<vm::Machine>(*b.m);
  b.native = std::make_unique<vm::Machine>(*b.m);
  b.native->useCompiled(compiled.code);
  for (vm::Machine* vm : {b.interp.get(), b.native.get()}) {
    vm->setBudget(budget);
    ASSERT_TRUE(vm->coldStart());
  }
}

// Runs MAIN `scans` times, 10 ms apart, on both backends; returns the number of faulted scans.
int runMainOnBoth(BothBackends& b, int scans) {
  const bc::ProgramInstance& main = b.m->programs.at(0);
  int faults = 0;
  for (int k = 0; k < scans; ++k) {
    expectSameRun(*b.interp, *b.native, *b.m, main.pou, main.address, k * 10'000'000LL, faults);
    if (::testing::Test::HasFatalFailure()) break;
  }
  return faults;
}

TEST(Aot, NestedFaultReportsTheSameCallStack) {
  const char* source = R"(
FUNCTION Ratio : DINT
VAR_INPUT a, b : DINT; END_VAR
Ratio := a / b;
END_FUNCTION
FUNCTION_BLOCK FB_Scale
VAR_INPUT d : DINT; END_VAR
VAR_OUTPUT q : DINT; END_VAR
q := Ratio(100, d);
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR s : FB_Scale; n : DINT := 2; END_VAR
n := n - 1;
s(d := n);
END_PROGRAM
)";
  BothBackends b;
  ASSERT_NO_FATAL_FAILURE(prepare(source, b));
  ASSERT_EQ(runMainOnBoth(b, 2), 1);
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
  const std::string report = b.native->fault().describe(*b.m);
  EXPECT_EQ(report.rfind("division by zero at main.st:4:", 0), 0u) << report;
  EXPECT_EQ(b.native->fault().callStack.size(), 2u) << report;
}

// Every standard FB (compiled from vm/native_fbs_c.def into the generated C) and small user
// FBs and functions (inlined by the C compiler) with values live across the calls, over
// enough scans for the timers to run out and the counters to wrap.
TEST(Aot, InlinedStandardAndUserFbsRunAsOnTheInterpreter) {
  const char* source = R"(
FUNCTION Twice : DINT
VAR_INPUT x : DINT; END_VAR
Twice := x + x;
END_FUNCTION
FUNCTION_BLOCK FB_Acc
VAR_INPUT x : REAL; on : BOOL; END_VAR
VAR_OUTPUT y : REAL; high : BOOL; END_VAR
IF on THEN y := y + (x - y) * 0.25; ELSE y := 0.0; END_IF
high := y > 3.0;
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR
  ton1 : TON; tof1 : TOF; tp1 : TP; ctu1 : CTU; ctd1 : CTD; ctud1 : CTUD;
  rt : R_TRIG; ft : F_TRIG; sr1 : SR; rs1 : RS;
  acc : ARRAY[1..3] OF FB_Acc;
  k : INT; n : DINT; sum : DINT; ySum : REAL; tick : BOOL;
END_VAR
n := n + 1;
tick := (n MOD 3) = 0;
ton1(IN := NOT ton1.Q, PT := T#30MS);
tof1(IN := tick, PT := T#20MS);
tp1(IN := ton1.Q, PT := T#40MS);
ctu1(CU := ton1.Q, RESET := ctu1.Q, PV := 4);
ctd1(CD := tick, LOAD := ctd1.Q, PV := 3);
ctud1(CU := tick, CD := tp1.Q, RESET := ctud1.QU, LOAD := FALSE, PV := 5);
rt(CLK := tick);
ft(CLK := tof1.Q);
sr1(SET1 := rt.Q, RESET := ft.Q);
rs1(SET := ft.Q, RESET1 := rt.Q);
sum := 0;
ySum := 0.0;
FOR k := 1 TO 3 DO
  acc[k](x := INT_TO_REAL(ctu1.CV + k), on := NOT sr1.Q1);
  sum := sum + Twice(k) * Twice(INT_TO_DINT(ctud1.CV)) + n;
  IF acc[k].high THEN ySum := ySum + acc[k].y; END_IF
END_FOR
END_PROGRAM
)";
  BothBackends b;
  ASSERT_NO_FATAL_FAILURE(prepare(source, b));
  EXPECT_EQ(runMainOnBoth(b, 300), 0);
}

// A fault and the watchdog inside an FB the C compiler inlines: same pc, source location and
// call stack as the interpreter (expectSameRun compares the reports).
TEST(Aot, FaultsInsideAnInlinedFbReportTheCallSite) {
  const char* source = R"(
FUNCTION_BLOCK FB_Spin
VAR_INPUT n, d : DINT; END_VAR
VAR_OUTPUT q : DINT; END_VAR
WHILE n > 0 DO
  q := q + 1;
END_WHILE
q := 100 / d;
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR s : FB_Spin; scan : DINT; END_VAR
scan := scan + 1;
s(n := scan / 3, d := 2 - scan);
END_PROGRAM
)";
  BothBackends b;
  ASSERT_NO_FATAL_FAILURE(prepare(source, b, 1000));
  const bc::ProgramInstance& main = b.m->programs.at(0);
  const bc::FaultKind expected[] = {bc::FaultKind::None, bc::FaultKind::DivisionByZero, bc::FaultKind::WatchdogBudget};
  const char* where[] = {"", "main.st:8:", "main.st:6:"};  // the loop's backward jump
  int faults = 0;
  for (int scan = 0; scan < 3; ++scan) {
    SCOPED_TRACE(scan + 1);
    ASSERT_NO_FATAL_FAILURE(expectSameRun(*b.interp, *b.native, *b.m, main.pou, main.address, 0, faults));
    EXPECT_EQ(faults, scan);
    if (scan == 0) continue;
    const vm::FaultInfo& fault = b.native->fault();
    EXPECT_EQ(fault.kind, expected[scan]);
    EXPECT_NE(fault.describe(*b.m).find(where[scan]), std::string::npos) << fault.describe(*b.m);
    EXPECT_EQ(fault.callStack.size(), 1u);
  }
}

// A caller keeps r7 across a call and reads back r4, which the callee (window at r2) sets as
// its r2; r6 is dead after the call. The plan stores and reloads only what is read afterwards
// and the callee writes back only its r2.
TEST(Aot, RegisterPlanMovesOnlyTheRegistersReadAfterACall) {
  test::ModuleBuilder b(64);
  b.beginPou("Leaf", 4);
  b.emit(test::asbx(Op::LDI, 2, 7));
  b.emit(test::abc(Op::ADD, 2, 2, 1));  // reads this (r1): the callee's inputs are r0..r1
  b.emit(test::abc(Op::RET));
  b.beginPou("Caller", 8);
  b.emit(test::asbx(Op::LDI, 2, 0));
  b.emit(test::abc(Op::MOV, 3, 1));
  b.emit(test::asbx(Op::LDI, 6, 5));
  b.emit(test::asbx(Op::LDI, 7, 9));
  const uint32_t call = b.emit(test::abx(Op::CALL, 2, 0)) - b.m.pous[1].codeStart;
  b.emit(test::abc(Op::ADD, 6, 4, 7));
  b.emit(test::abc(Op::ST_32, 6, 1, 0));
  b.emit(test::abc(Op::RET));
  ASSERT_EQ(bc::verifyModule(b.m), "");

  const aot::RegisterPlan plan = aot::planRegisters(b.m);
  EXPECT_EQ(plan.inputs[0], (aot::RegisterSet{false, true}));
  EXPECT_EQ(plan.pous[0].writeBack, (aot::RegisterSet{false, false, true, false}));
  EXPECT_EQ(plan.pous[1].writeBack, aot::RegisterSet(8, false));  // nobody calls it
  EXPECT_EQ(plan.pous[1].liveAfterCall[call], (aot::RegisterSet{false, true, false, false, true, false, false, true}));

  const aot::CompileResult compiled = aot::compileModule(b.m, testOptions());
  ASSERT_TRUE(compiled.code) << compiled.error;
  vm::Machine interp(b.m), native(b.m);
  native.useCompiled(compiled.code);
  ASSERT_TRUE(interp.coldStart());
  ASSERT_TRUE(native.coldStart());
  int faults = 0;
  ASSERT_NO_FATAL_FAILURE(expectSameRun(interp, native, b.m, 1, 32, 0, faults));
  uint32_t stored = 0;
  std::memcpy(&stored, native.memory() + 32, sizeof stored);
  EXPECT_EQ(stored, 7u + 32u + 9u);
}

// FB_k adds k and calls Twice (a small leaf, copied into every unit that calls it), FB_Chain
// calls all of them and a division that faults on the 7th scan, MAIN calls FB_Chain: `edit`
// replaces FB_3's body.
std::string manyFbs(const std::string& edit = "") {
  std::string s = "FUNCTION Twice : DINT\nVAR_INPUT x : DINT; END_VAR\nTwice := x + x;\nEND_FUNCTION\n"
                  "FUNCTION Ratio : DINT\nVAR_INPUT a, b : DINT; END_VAR\nRatio := a / b;\nEND_FUNCTION\n";
  for (int k = 0; k < 8; ++k) {
    s += "FUNCTION_BLOCK FB_" + std::to_string(k) + "\nVAR_INPUT x : DINT; END_VAR\nVAR_OUTPUT q : DINT; END_VAR\n";
    s += k == 3 && !edit.empty() ? edit : "q := (Twice(x) + " + std::to_string(k) + ") MOD 1000;\n";
    s += "END_FUNCTION_BLOCK\n";
  }
  s += "FUNCTION_BLOCK FB_Chain\nVAR_INPUT n : DINT; END_VAR\nVAR_OUTPUT q : DINT; END_VAR\nVAR\n";
  for (int k = 0; k < 8; ++k) s += "  f" + std::to_string(k) + " : FB_" + std::to_string(k) + ";\n";
  s += "END_VAR\nf0(x := n);\n";
  for (int k = 1; k < 8; ++k) s += "f" + std::to_string(k) + "(x := f" + std::to_string(k - 1) + ".q);\n";
  s += "q := f7.q + Ratio(100, 7 - n);\nEND_FUNCTION_BLOCK\n";
  return s + "PROGRAM MAIN\nVAR c : FB_Chain; n : DINT; END_VAR\nn := n + 1;\nc(n := n);\nEND_PROGRAM\n";
}

// A module of many POUs in units of one POU each, compiled four at a time: same memory after
// every scan as the interpreter, and the same fault (division in Ratio, called from FB_Chain
// in another unit) with the same location and call stack.
TEST(Aot, ManyPousSplitIntoUnitsRunAsOnTheInterpreter) {
  aot::CompileOptions options = testOptions();
  options.unitInstructions = 1;
  options.jobs = 4;
  BothBackends b;
  aot::CompileResult compiled;
  ASSERT_NO_FATAL_FAILURE(prepare(manyFbs(), b, 50'000'000, options, &compiled));
  EXPECT_EQ(compiled.units, b.m->pous.size() + 1);  // one per POU and the entry table
  EXPECT_EQ(runMainOnBoth(b, 20), 1);
  const std::string report = b.native->fault().describe(*b.m);
  EXPECT_NE(report.find("division by zero at main.st:7:"), std::string::npos) << report;
  EXPECT_EQ(b.native->fault().callStack.size(), 2u) << report;
}

// Editing one FB recompiles its unit only (a new constant), or its unit and the entry table
// (which holds where each POU starts) when the edit moves the code of every POU after it; the
// edited module still runs as on the interpreter.
TEST(Aot, AnEditRecompilesOnlyItsUnit) {
  aot::CompileOptions options;
  options.cacheDir = (fs::path(VIRTCOM_AOT_TEST_CACHE) / ("edit-test-" + std::to_string(getpid()))).string();
  options.unitInstructions = 1;
  fs::remove_all(options.cacheDir);
  const std::string edits[] = {"", "q := (Twice(x) + 30) MOD 1000;\n", "q := (Twice(x) + 30) MOD 1000;\nq := q + 1;\n"};
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE(round);
    BothBackends b;
    aot::CompileResult compiled;
    ASSERT_NO_FATAL_FAILURE(prepare(manyFbs(edits[round]), b, 50'000'000, options, &compiled));
    EXPECT_FALSE(compiled.fromCache);
    EXPECT_EQ(compiled.unitsCompiled, round == 0 ? compiled.units : static_cast<size_t>(round));
    EXPECT_EQ(runMainOnBoth(b, 3), 0);
  }
  fs::remove_all(options.cacheDir);
}

// A callee's register count grows with its statements (statement registers rotate,
// codegen_stmt.cpp); a CALL's register-stack check reads it as a constant of the callee's unit,
// so the caller's unit keeps its text when only the callee is edited.
TEST(Aot, ACalleesRegisterCountIsInItsUnitOnly) {
  struct Generated {
    uint16_t fb3Registers = 0;
    std::vector<aot::CUnit> units;
    std::string unitOf(const std::string& cName) const {  // '_' is written _5f (c_source.cpp)
      for (const aot::CUnit& u : units)
        if (u.source.find("static int s_" + cName + "(") != std::string::npos) return u.source;
      return "";
    }
  };
  const auto generate = [](const std::string& source) {
    SourceManager sources;
    Diagnostics diags;
    const std::unique_ptr<bc::Module> m = st::compileProgram({{"main.st", source}}, sources, diags);
    Generated g;
    if (!m) return g;
    for (const bc::PouInfo& p : m->pous)
      if (p.name == "FB_3") g.fb3Registers = p.numRegs;
    g.units = aot::generateCUnits(*m, 1);
    return g;
  };
  const Generated before = generate(manyFbs());
  const Generated after = generate(manyFbs("q := (Twice(x) + 3) MOD 1000;\nq := q * 7 MOD 1000;\nq := q + x;\n"));
  ASSERT_FALSE(before.unitOf("FB_5fChain").empty());
  EXPECT_GT(after.fb3Registers, before.fb3Registers);
  EXPECT_EQ(after.unitOf("FB_5fChain"), before.unitOf("FB_5fChain"));
  EXPECT_NE(after.unitOf("FB_5f3"), before.unitOf("FB_5f3"));
  EXPECT_NE(before.unitOf("FB_5fChain").find("nr_FB_5f3"), std::string::npos);
  EXPECT_NE(after.unitOf("FB_5f3").find("nr_FB_5f3 = " + std::to_string(after.fb3Registers) + "u;"), std::string::npos);
}

// MAIN of some 5,000 instructions, cut into chunks (functions) spread over units: an early
// RETURN from the first chunk on every third scan, a division by zero in a later chunk on the
// 5th scan and the watchdog in a loop of the last chunk from the 7th scan on.
TEST(Aot, AHugePouIsCutIntoChunksThatRunAsOnTheInterpreter) {
  std::string source = "PROGRAM MAIN\nVAR a : ARRAY[0..15] OF DINT; i, n, d : DINT; x : REAL; END_VAR\nn := n + 1;\n";
  auto statements = [&source](int from, int to) {
    for (int k = from; k < to; ++k)
      source += "a[" + std::to_string(k % 16) + "] := (a[" + std::to_string(k * 7 % 16) + "] + n * " + std::to_string(k) +
                ") MOD 1000; x := x * 0.5 + DINT_TO_REAL(a[" + std::to_string(k % 16) + "]);\n";
  };
  statements(0, 150);
  source += "IF n MOD 3 = 0 THEN RETURN; END_IF;\n";
  statements(150, 300);
  source += "d := 100 / (5 - n);\n";
  statements(300, 450);
  source += "i := 0;\nWHILE i < n * 1000 DO i := i + 1; END_WHILE;\nEND_PROGRAM\n";
  aot::CompileOptions options = testOptions();
  options.unitInstructions = 2000;
  BothBackends b;
  aot::CompileResult compiled;
  ASSERT_NO_FATAL_FAILURE(prepare(source, b, 6500, options, &compiled));
  ASSERT_GT(b.m->pous.at(b.m->programs.at(0).pou).codeSize, 4000u);
  EXPECT_GE(compiled.units, 3u);  // MAIN in two units or more, and the table
  EXPECT_EQ(runMainOnBoth(b, 10), 4);  // 5: division, 7, 8, 10: watchdog
}

bc::Module tinyModule() {
  test::ModuleBuilder b(64);
  b.beginPou("P", 2);
  b.emit(test::abc(Op::RET));
  return b.m;
}

TEST(Aot, WithoutACompilerReportsWhy) {
  aot::CompileOptions o = testOptions();
  o.compiler = "virtcom-no-such-compiler";
  const aot::CompileResult r = aot::compileModule(tinyModule(), o);
  EXPECT_EQ(r.code, nullptr);
  EXPECT_NE(r.error.find("virtcom-no-such-compiler"), std::string::npos) << r.error;
}

TEST(Aot, AFailingCompilerReportsWhy) {
  aot::CompileOptions o = testOptions();
  o.compiler = "false";
  const aot::CompileResult r = aot::compileModule(tinyModule(), o);
  EXPECT_EQ(r.code, nullptr);
  EXPECT_NE(r.error.find("the C compiler failed"), std::string::npos) << r.error;
}

TEST(Aot, RefusesAModuleThatDoesNotVerify) {
  bc::Module m = tinyModule();
  m.code.back() = test::abc(Op::NOP);  // no RET at the end
  const aot::CompileResult r = aot::compileModule(m, testOptions());
  EXPECT_EQ(r.code, nullptr);
  EXPECT_NE(r.error.find("does not verify"), std::string::npos) << r.error;
}

TEST(Aot, ReusesTheCachedObject) {
  aot::CompileOptions o;
  o.cacheDir = (fs::path(VIRTCOM_AOT_TEST_CACHE) / ("cache-test-" + std::to_string(getpid()))).string();
  fs::remove_all(o.cacheDir);
  const aot::CompileResult first = aot::compileModule(tinyModule(), o);
  ASSERT_TRUE(first.code) << first.error;
  EXPECT_FALSE(first.fromCache);
  const aot::CompileResult second = aot::compileModule(tinyModule(), o);
  ASSERT_TRUE(second.code) << second.error;
  EXPECT_TRUE(second.fromCache);
  const bc::Module module = tinyModule();  // the Machine keeps a reference: not a temporary
  vm::Machine vm(module);
  vm.useCompiled(second.code);
  EXPECT_TRUE(vm.run(0, 0));
  fs::remove_all(o.cacheDir);
}

// `--backend auto` looks for a former compile before the first scan by the cheap key: nothing
// before any compile, the same shared object after one, nothing for a module that differs in
// any part the C generator reads (a constant, an index descriptor, a POU's registers, the unit
// size), and it never compiles.
TEST(Aot, LoadsAFormerCompileByTheCheapKeyOnly) {
  aot::CompileOptions o;
  o.cacheDir = (fs::path(VIRTCOM_AOT_TEST_CACHE) / ("key-test-" + std::to_string(getpid()))).string();
  fs::remove_all(o.cacheDir);
  std::mt19937 rng(7);
  const bc::Module m = randomModule(rng, 6);
  ASSERT_FALSE(aot::moduleKey(m, o.unitInstructions).empty()) << "the test binary has no build id";
  const aot::CompileResult cold = aot::loadCachedModule(m, o);
  EXPECT_EQ(cold.code, nullptr);
  EXPECT_EQ(cold.error, "not in the cache");
  EXPECT_FALSE(fs::exists(o.cacheDir)) << "a look-up writes nothing";

  const aot::CompileResult compiled = aot::compileModule(m, o);
  ASSERT_TRUE(compiled.code) << compiled.error;
  const aot::CompileResult warm = aot::loadCachedModule(m, o);
  ASSERT_TRUE(warm.code) << warm.error;
  EXPECT_TRUE(warm.fromCache);
  vm::Machine interp(m), machine(m);
  machine.useCompiled(warm.code);
  for (vm::Machine* vm : {&interp, &machine}) {
    vm->setBudget(200);
    ASSERT_TRUE(vm->coldStart());
  }
  int faulted = 0;
  for (uint32_t pou = 0; pou < m.pous.size(); ++pou)
    ASSERT_NO_FATAL_FAILURE(expectSameRun(interp, machine, m, pou, 0, 1000, faulted));

  const auto key = aot::moduleKey(m, o.unitInstructions);
  std::vector<bc::Module> others(4, m);
  if (others[0].constants.empty()) others[0].constants.push_back(1);
  else others[0].constants.back() ^= 1;
  others[1].indexes.push_back({});
  others[2].pous.back().numRegs += 1;
  others[3].code.back().a ^= 1;
  for (size_t k = 0; k < others.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_NE(aot::moduleKey(others[k], o.unitInstructions), key);
  }
  EXPECT_NE(aot::moduleKey(m, o.unitInstructions + 1), key);
  aot::CompileOptions otherUnits = o;
  otherUnits.unitInstructions = 1;
  EXPECT_EQ(aot::loadCachedModule(m, otherUnits).code, nullptr);
  fs::remove_all(o.cacheDir);
}

// `--backend aot` takes a former compile only from the compiler it would run now; `auto` from any.
TEST(Aot, TheCheapKeyServesAotOnlyTheSameCompilersCode) {
  aot::CompileOptions o;
  o.cacheDir = (fs::path(VIRTCOM_AOT_TEST_CACHE) / ("compiler-key-test-" + std::to_string(getpid()))).string();
  fs::remove_all(o.cacheDir);
  std::mt19937 rng(11);
  const bc::Module m = randomModule(rng, 3);
  ASSERT_TRUE(aot::compileModule(m, o).code);
  EXPECT_TRUE(aot::loadCachedModule(m, o, aot::CachedCompiler::Same).code);
  aot::CompileOptions otherCompiler = o;
  otherCompiler.compiler = "virtcom-no-such-compiler";
  const aot::CompileResult refused = aot::loadCachedModule(m, otherCompiler, aot::CachedCompiler::Same);
  EXPECT_EQ(refused.code, nullptr);
  EXPECT_EQ(refused.error, "not in the cache");
  EXPECT_TRUE(aot::loadCachedModule(m, otherCompiler, aot::CachedCompiler::Any).code);
  fs::remove_all(o.cacheDir);
}

}  // namespace
}  // namespace virtcom
