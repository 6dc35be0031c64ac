// The AOT backend against the interpreter on random bytecode (every opcode, faults, calls,
// natives), on a compiled ST program with a nested fault, and its fallbacks and cache.
// The golden programs are compared in tests/golden (Golden.AotMatchesInterpreter).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "../vm/random_instr.hpp"
#include "../vm/test_module_builder.hpp"
#include "aot/compile.hpp"
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
  test::ModuleBuilder b(256);
  b.m.stackSize = 512;
  b.m.maxCallDepth = 8;
  b.m.registerStackSize = 64;
  for (int k = 0; k < 3; ++k) b.constant(std::uniform_int_distribution<uint64_t>()(rng) % 600);
  for (int k = 0; k < 3; ++k)
    b.m.indexes.push_back({static_cast<int64_t>(rng() % 600) - 300, 1 + rng() % 300, rng() % 9});
  for (size_t i = 16; i < b.m.initialImage.size(); ++i) b.m.initialImage[i] = static_cast<uint8_t>(rng() % 4 ? rng() : 0);
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

TEST(Aot, RandomBytecodeRunsAsOnTheInterpreter) {
  std::mt19937 rng(20261201);
  const bc::Module m = randomModule(rng, 200);
  const aot::CompileResult compiled = aot::compileModule(m, testOptions());
  ASSERT_TRUE(compiled.code) << compiled.error;
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
  SourceManager sources;
  Diagnostics diags;
  auto m = st::compileProgram({{"main.st", source}}, sources, diags);
  ASSERT_NE(m, nullptr) << diags.render(sources);
  const aot::CompileResult compiled = aot::compileModule(*m, testOptions());
  ASSERT_TRUE(compiled.code) << compiled.error;
  vm::Machine interp(*m), native(*m);
  native.useCompiled(compiled.code);
  ASSERT_TRUE(interp.coldStart());
  ASSERT_TRUE(native.coldStart());
  const bc::ProgramInstance& main = m->programs.at(0);
  int faults = 0;
  ASSERT_NO_FATAL_FAILURE(expectSameRun(interp, native, *m, main.pou, main.address, 0, faults));
  ASSERT_NO_FATAL_FAILURE(expectSameRun(interp, native, *m, main.pou, main.address, 10'000'000, faults));
  ASSERT_EQ(faults, 1);
  const std::string report = native.fault().describe(*m);
  EXPECT_EQ(report.rfind("division by zero at main.st:4:", 0), 0u) << report;
  EXPECT_EQ(native.fault().callStack.size(), 2u) << report;
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

}  // namespace
}  // namespace virtcom
