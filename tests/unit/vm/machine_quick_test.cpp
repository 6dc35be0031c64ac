// Quickened frame/instance accesses (vm/quicken.hpp): which POUs and instructions are quickened,
// and that an activation whose fp or this fails the entry check runs the checked code, so the
// fault stays at the access with its own pc and line.
#include "vm/quicken.hpp"

#include <gtest/gtest.h>

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

constexpr uint32_t kStatic = 256;

// FB: r2 := this->[8] (DINT); this->[12] := r2 + 1; MAIN calls FB with this = r[3] (from a constant).
ModuleBuilder callerAndFb(uint64_t self) {
  ModuleBuilder b(kStatic);
  b.m.stackSize = 256;
  b.constant(self);
  b.beginPou("MAIN", 6);
  b.emit(abx(Op::LDK, 5, 0));
  b.emit(abx(Op::ENTER, 2, 1), 3);
  b.emit(abc(Op::MOV, 3, 5));
  b.emit(abx(Op::CALL, 2, 1), 4);
  b.emit(abc(Op::RET));
  b.beginPou("FB", 3, 0, 0, bc::PouKind::FunctionBlock);
  b.emit(abc(Op::LD_I32, 2, 1, 8), 10);
  b.emit(abc(Op::ADDI, 2, 2, 1));
  b.emit(abc(Op::ST_32, 2, 1, 12), 11);
  b.emit(abc(Op::RET));
  return b;
}

TEST(MachineQuick, AccessesRelativeToReadOnlyFpOrThisAreQuickened) {
  ModuleBuilder b = callerAndFb(64);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[5].op, vm::quickOpcode(vm::QuickOp::LD_I32));
  EXPECT_EQ(q.code[7].op, vm::quickOpcode(vm::QuickOp::ST_32));
  EXPECT_EQ(q.code[6].op, Op::ADDI);
  EXPECT_TRUE(q.entry[1].admits(kStatic, 64));
  EXPECT_FALSE(q.entry[1].admits(kStatic, 8));                        // this below the null guard
  EXPECT_FALSE(q.entry[1].admits(kStatic, b.m.memorySize() - 15));    // this->[12..16) past the end
  EXPECT_TRUE(q.entry[1].admits(kStatic, b.m.memorySize() - 16));
}

TEST(MachineQuick, APouThatWritesThisIsNotQuickened) {
  ModuleBuilder b = callerAndFb(64);
  b.m.code[6] = abc(Op::ADDI, 1, 1, 4);  // this += 4 inside FB
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[5].op, Op::LD_I32);
  EXPECT_EQ(q.code[7].op, Op::ST_32);
}

TEST(MachineQuick, QuickenedAccessesComputeTheSame) {
  ModuleBuilder b = callerAndFb(64);
  b.poke<int32_t>(64 + 8, 41);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  int32_t v;
  std::memcpy(&v, vm.memory() + 64 + 12, 4);
  EXPECT_EQ(v, 42);
}

TEST(MachineQuick, AThisOutsideMemoryFaultsAtTheAccessAsBefore) {
  // this = memory size - 10: the load of this->[8..12) fails; with this = 4 it is below the guard.
  for (uint64_t self : {uint64_t{4}, uint64_t{0}, uint64_t{0xffffffff}}) {
    ModuleBuilder b = callerAndFb(self);
    ASSERT_EQ(bc::verifyModule(b.m), "");
    vm::Machine vm(b.m);
    vm.coldStart();
    ASSERT_FALSE(vm.run(0, 0));
    EXPECT_EQ(vm.fault().kind, bc::FaultKind::InvalidPointer);
    EXPECT_EQ(vm.fault().pc, 5u);
    EXPECT_EQ(vm.fault().loc.line, 10u);
    ASSERT_EQ(vm.fault().callStack.size(), 1u);
    EXPECT_EQ(vm.fault().callStack[0], 3u);
  }
  // Inside memory but the store's end past it: the load passes, the store faults.
  ModuleBuilder b = callerAndFb(0);
  b.m.constants[0] = b.m.memorySize() - 14;
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().pc, 7u);
  EXPECT_EQ(vm.fault().loc.line, 11u);
}

TEST(MachineQuick, TheTopPouIsCheckedOnEntryToo) {
  ModuleBuilder b = callerAndFb(64);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  EXPECT_FALSE(vm.run(1, 2));  // FB run directly with this = 2
  EXPECT_EQ(vm.fault().pc, 5u);
  EXPECT_TRUE(vm.run(1, 64)) << vm.fault().describe(b.m);
}

}  // namespace
}  // namespace virtcom
