// The fused compare-and-branch instructions (JEQ .. JGEK): each jumps exactly when its relation
// holds, on signed, unsigned and boundary values; a taken backward one consumes the watchdog
// budget like JMP and faults at its own pc.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

using bc::Op;
using test::abc;
using test::abx;
using test::asbx;
using test::ModuleBuilder;

constexpr uint32_t kOut = 16;

// r2 = x, r3 = y (from constants); the branch skips a store of 1 to kOut; returns whether it jumped.
bool jumps(bc::Instr branch, uint64_t x, uint64_t y = 0) {
  ModuleBuilder b;
  b.constant(x);
  b.constant(y);
  b.beginPou("MAIN", 4);
  b.emit(abx(Op::LDK, 2, 0));
  b.emit(abx(Op::LDK, 3, 1));
  b.emit(branch);
  b.emit(abc(Op::STK_8, 1, 1, kOut));  // this = 0: mem[kOut] = 1
  b.emit(abc(Op::RET));
  EXPECT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  EXPECT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  return vm.memory()[kOut] == 0;
}

TEST(MachineBranch, RegisterFormsJumpWhenTheRelationHolds) {
  const std::vector<uint64_t> values = {0, 1, 2, UINT64_MAX, UINT64_MAX - 1, uint64_t{1} << 63, (uint64_t{1} << 63) - 1};
  struct Case {
    Op op;
    std::function<bool(uint64_t, uint64_t)> holds;
  };
  const std::vector<Case> cases = {
      {Op::JEQ, [](uint64_t x, uint64_t y) { return x == y; }},
      {Op::JNE, [](uint64_t x, uint64_t y) { return x != y; }},
      {Op::JLT_I, [](uint64_t x, uint64_t y) { return static_cast<int64_t>(x) < static_cast<int64_t>(y); }},
      {Op::JLE_I, [](uint64_t x, uint64_t y) { return static_cast<int64_t>(x) <= static_cast<int64_t>(y); }},
      {Op::JLT_U, [](uint64_t x, uint64_t y) { return x < y; }},
      {Op::JLE_U, [](uint64_t x, uint64_t y) { return x <= y; }},
  };
  for (const Case& c : cases)
    for (uint64_t x : values)
      for (uint64_t y : values)
        EXPECT_EQ(jumps(abc(c.op, 2, 3, 1), x, y), c.holds(x, y)) << bc::opName(c.op) << " " << x << " " << y;
}

TEST(MachineBranch, ConstantFormsCompareWithTheSignedImmediate) {
  const std::vector<int64_t> values = {-32769, -32768, -5, -1, 0, 1, 4, 5, 6, 32767, INT64_MIN, INT64_MAX};
  struct Case {
    Op op;
    std::function<bool(int64_t, int64_t)> holds;
  };
  const std::vector<Case> cases = {
      {Op::JEQK, [](int64_t x, int64_t k) { return x == k; }}, {Op::JNEK, [](int64_t x, int64_t k) { return x != k; }},
      {Op::JLTK, [](int64_t x, int64_t k) { return x < k; }},  {Op::JLEK, [](int64_t x, int64_t k) { return x <= k; }},
      {Op::JGTK, [](int64_t x, int64_t k) { return x > k; }},  {Op::JGEK, [](int64_t x, int64_t k) { return x >= k; }},
  };
  for (const Case& c : cases)
    for (int64_t k : {int64_t{-32768}, int64_t{-5}, int64_t{0}, int64_t{5}, int64_t{32767}})
      for (int64_t x : values)
        EXPECT_EQ(jumps(abc(c.op, 2, 1, static_cast<uint16_t>(k)), static_cast<uint64_t>(x)), c.holds(x, k))
            << bc::opName(c.op) << " " << x << " " << k;
}

TEST(MachineBranch, TakenBackwardBranchesConsumeTheBudgetAndFaultAtTheirPc) {
  // r2 counts up from 0; JLTK jumps back to the ADDI while r2 < 1000: 999 taken backward jumps.
  ModuleBuilder b;
  b.beginPou("MAIN", 4);
  b.emit(asbx(Op::LDI, 2, 0));
  b.emit(abc(Op::ADDI, 2, 2, 1), 7);
  b.emit(abc(Op::JLTK, 2, static_cast<uint16_t>(-2), 1000), 8);
  b.emit(abc(Op::RET));
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.setBudget(999);
  EXPECT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  vm.setBudget(998);
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, bc::FaultKind::WatchdogBudget);
  EXPECT_EQ(vm.fault().pc, 2u);
  EXPECT_EQ(vm.fault().loc.line, 8u);
}

}  // namespace
}  // namespace virtcom
