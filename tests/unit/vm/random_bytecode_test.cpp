// Robustness: random bytecode either fails verification or runs to completion / a fault
// without touching memory outside the image (ASan/UBSan in the test build catch the rest).
#include <gtest/gtest.h>

#include <random>

#include "bytecode/verifier.hpp"
#include "random_instr.hpp"
#include "test_module_builder.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

using bc::Op;
using test::randomInstr;

TEST(RandomBytecode, VerifiedModulesRunSafely) {
  std::mt19937 rng(20240611);
  int verified = 0, completed = 0;
  for (int round = 0; round < 20000; ++round) {
    test::ModuleBuilder b = test::randomModuleTables(rng);
    for (int p = 0; p < 3; ++p) {
      const auto regs = static_cast<uint16_t>(2 + rng() % 10);
      const uint32_t size = 2 + rng() % 12;
      b.beginPou("P" + std::to_string(p), regs, rng() % 64, 16 + rng() % 128);
      const uint32_t start = b.pc();
      for (uint32_t i = 0; i + 1 < size; ++i) b.emit(randomInstr(rng, regs, b.pc(), start, size), 1 + i);
      b.emit(rng() % 8 ? bc::Instr::abc(Op::RET, 0, 0, 0) : randomInstr(rng, regs, b.pc(), start, size));
    }
    if (!bc::verifyModule(b.m).empty()) continue;
    ++verified;
    vm::Machine vm(b.m);
    vm.setBudget(200);
    vm.coldStart();
    for (uint32_t p = 0; p < 3; ++p) {
      const bool ok = vm.run(p, static_cast<uint32_t>(rng() % 300));
      completed += ok;
      if (!ok) (void)vm.fault().describe(b.m);
      EXPECT_EQ(vm.stackPointer(), b.m.staticSize);
    }
  }
  EXPECT_GT(verified, 100);
  EXPECT_GT(completed, 50);
}

}  // namespace
}  // namespace virtcom
