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
  // FB has no frame, and its ENTER is followed by the MOV of this and the CALL
  EXPECT_EQ(q.code[1].op, vm::quickOpcode(vm::QuickOp::ENTER0_CALL));
  EXPECT_EQ(q.code[2].op, Op::MOV);   // stays, for jumps to it
  EXPECT_EQ(q.code[3].op, Op::CALL);
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

// A FOR loop as code generation emits it (Program, this = 64): i := start (this->[0], INT or
// DINT); DO count := count + 1 (r4); i := i + step; reload i; WHILE i <= end; this->[8] := count.
// With `jumpIntoStore`, the first pass enters at the store (pc 6), as a jump to it would.
ModuleBuilder forLoop(bool dint, int16_t start, int32_t end, int16_t step, bool jumpIntoStore = false) {
  ModuleBuilder b(kStatic);
  b.beginPou("MAIN", 5, 0, 0, bc::PouKind::Program);
  b.emit(abc(dint ? Op::STK_32 : Op::STK_16, static_cast<uint16_t>(start), 1, 0));  // 0
  b.emit(asbx(Op::LDI, 3, end));                                                    // 1
  b.emit(dint ? abc(Op::LD_I32, 2, 1, 0) : abc(Op::LD_I16, 2, 1, 0));               // 2
  b.emit(asbx(Op::JMP, 0, jumpIntoStore ? 2 : 0));                                  // 3
  b.emit(abc(Op::ADDI, 4, 4, 1), 20);                                               // 4: the body
  b.emit(abc(Op::ADDI, 2, 2, static_cast<uint16_t>(step)), 21);                     // 5
  b.emit(abc(dint ? Op::ST_32 : Op::ST_16, 2, 1, 0));                               // 6
  b.emit(abc(dint ? Op::LD_I32 : Op::LD_I16, 2, 1, 0));                             // 7
  b.emit(abc(Op::JLE_I, 2, 3, static_cast<uint16_t>(-5)));                          // 8: to 4
  b.emit(abc(Op::ST_32, 4, 1, 8));                                                  // 9
  b.emit(abc(Op::RET));                                                             // 10
  return b;
}

int32_t loaded(const vm::Machine& vm, uint32_t addr, bool dint) {
  if (dint) {
    int32_t v;
    std::memcpy(&v, vm.memory() + addr, 4);
    return v;
  }
  int16_t v;
  std::memcpy(&v, vm.memory() + addr, 2);
  return v;
}

TEST(MachineQuick, AForLoopsStepStoreReloadAndTestAreOneDispatch) {
  for (const bool dint : {false, true}) {
    ModuleBuilder b = forLoop(dint, -3, 40, 4);
    ASSERT_EQ(bc::verifyModule(b.m), "");
    const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
    EXPECT_EQ(q.code[5].op, vm::quickOpcode(dint ? vm::QuickOp::FOR_NEXT_I32 : vm::QuickOp::FOR_NEXT_I16));
    // The three it covers stay, for jumps to them.
    EXPECT_EQ(q.code[6].op, vm::quickOpcode(dint ? vm::QuickOp::ST_32 : vm::QuickOp::ST_16));
    EXPECT_EQ(q.code[7].op, vm::quickOpcode(dint ? vm::QuickOp::LD_I32 : vm::QuickOp::LD_I16));
    EXPECT_EQ(q.code[8].op, Op::JLE_I);
    vm::Machine vm(b.m);
    vm.coldStart();
    vm.countInstructions(true);
    ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
    EXPECT_EQ(loaded(vm, 64, dint), 41);      // -3, 1, ..., 37, then 41 > 40
    EXPECT_EQ(loaded(vm, 64 + 8, true), 11);  // 11 passes
    EXPECT_EQ(vm.instructionsExecuted(), 4u + 11 * 5 + 2) << "counted as the instructions it stands for";
  }
}

TEST(MachineQuick, AJumpIntoAFusedForStepRunsTheRestOnItsOwn) {
  // Entering at the store skips the first step: i stays at its start for one pass more.
  for (const bool dint : {false, true}) {
    ModuleBuilder b = forLoop(dint, 0, 9, 3, true);
    ASSERT_EQ(bc::verifyModule(b.m), "");
    vm::Machine vm(b.m);
    vm.coldStart();
    ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
    EXPECT_EQ(loaded(vm, 64, dint), 12);
    EXPECT_EQ(loaded(vm, 64 + 8, true), 4);  // the body ran for i = 0, 3, 6, 9
  }
}

TEST(MachineQuick, AFusedForStepWrapsLikeItsStoreAndReloadAndKeepsTheWatchdog) {
  // INT: 32767 + 1 stores and reloads as -32768, which is <= 32767 again: an endless loop that
  // the watchdog stops at the JLE_I, as it does without the fusion.
  ModuleBuilder b = forLoop(false, 32766, 32767, 1);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.setBudget(70000);
  ASSERT_FALSE(vm.run(0, 64));
  EXPECT_EQ(vm.fault().kind, bc::FaultKind::WatchdogBudget);
  EXPECT_EQ(vm.fault().pc, 8u);
  // DINT: the sum in 64 bits would end the loop; the 32-bit reload wraps it to negative.
  ModuleBuilder d = forLoop(true, 0, 2147483647, 1);
  d.m.code[0] = abc(Op::NOP);                  // i starts as this->[0], set below
  d.poke<int32_t>(64, 2147483646);
  ASSERT_EQ(bc::verifyModule(d.m), "");
  vm::Machine dv(d.m);
  dv.coldStart();
  dv.setBudget(1000);
  ASSERT_FALSE(dv.run(0, 64));
  EXPECT_EQ(dv.fault().kind, bc::FaultKind::WatchdogBudget);
  EXPECT_EQ(dv.fault().pc, 8u);
  EXPECT_LT(loaded(dv, 64, true), 0);
}

TEST(MachineQuick, AStepOfTheRegisterThatIsAlsoTheBaseIsNotFused) {
  // r2 := this + 8, then r2 += 2; mem[r2] := r2; r2 := mem[r2]; the JLE_I: the shape of a FOR
  // loop's end, but the store's address is the stepped r2 (an element address, quickened).
  ModuleBuilder b(kStatic);
  b.beginPou("MAIN", 4, 0, 0, bc::PouKind::Program);
  b.emit(abc(Op::ADDI, 2, 1, 8));                              // 0
  b.emit(asbx(Op::LDI, 3, 0));                                 // 1
  b.emit(abc(Op::ADDI, 2, 2, 2));                              // 2
  b.emit(abc(Op::ST_16, 2, 2, 0));                             // 3
  b.emit(abc(Op::LD_I16, 2, 2, 0));                            // 4
  b.emit(abc(Op::JLE_I, 2, 3, 0));                             // 5: to 6 either way
  b.emit(abc(Op::RET));                                        // 6
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[2].op, Op::ADDI);
  EXPECT_EQ(q.code[3].op, vm::quickOpcode(vm::QuickOp::ST_16));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
  EXPECT_EQ(loaded(vm, 74, false), 74);
  EXPECT_EQ(loaded(vm, 72, false), 0);
}

TEST(MachineQuick, ExtensionsToTheIecWidthsAreSpecialisedAndComputeTheSame) {
  const uint64_t x = 0x1234'5678'9abc'def0;  // every byte with its top bit differently set
  ModuleBuilder b(kStatic);
  b.constant(x);
  b.beginPou("MAIN", 4, 0, 0, bc::PouKind::Program);
  uint32_t out = 0;
  for (const Op op : {Op::SEXT, Op::ZEXT})
    for (const uint16_t bits : {8, 16, 32, 12, 64}) {
      b.emit(abx(Op::LDK, 2, 0));
      b.emit(abc(op, 3, 2, bits));
      b.emit(abc(Op::ST_64, 3, 1, static_cast<uint16_t>(out)));
      out += 8;
    }
  b.emit(abc(Op::RET));
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[1].op, vm::quickOpcode(vm::QuickOp::SEXT8));
  EXPECT_EQ(q.code[4].op, vm::quickOpcode(vm::QuickOp::SEXT16));
  EXPECT_EQ(q.code[7].op, vm::quickOpcode(vm::QuickOp::SEXT32));
  EXPECT_EQ(q.code[10].op, Op::SEXT);  // 12 bits: the general form
  EXPECT_EQ(q.code[16].op, vm::quickOpcode(vm::QuickOp::ZEXT8));
  EXPECT_EQ(q.code[22].op, vm::quickOpcode(vm::QuickOp::ZEXT32));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
  const uint64_t expected[] = {0xffff'ffff'ffff'fff0, 0xffff'ffff'ffff'def0, 0xffff'ffff'9abc'def0, 0xffff'ffff'ffff'fef0, x,
                               0xf0, 0xdef0, 0x9abc'def0, 0xef0, x};
  for (size_t k = 0; k < std::size(expected); ++k) {
    uint64_t v;
    std::memcpy(&v, vm.memory() + 64 + 8 * k, 8);
    EXPECT_EQ(v, expected[k]) << k;
  }
}

// MAIN (this = 64): r2 := this->[0]; INDEX r3 := (r2 - 1) * 4 over [1..4]; ADD r4 := this + r3;
// this->[8] := r4 - this (the element's offset). With `jumpToAdd`, r3 := 12 and a jump to the ADD.
ModuleBuilder indexThenAdd(int32_t i, bool jumpToAdd = false) {
  ModuleBuilder b(kStatic);
  b.m.indexes.push_back({1, 4, 4});
  b.poke<int32_t>(64, i);
  b.beginPou("MAIN", 6, 0, 0, bc::PouKind::Program);
  b.emit(abc(Op::LD_I32, 2, 1, 0));                      // 0
  b.emit(asbx(Op::LDI, 3, 12));                          // 1
  b.emit(asbx(Op::JMP, 0, jumpToAdd ? 1 : 0));           // 2
  b.emit(abc(Op::INDEX, 3, 2, 0), 30);                   // 3
  b.emit(abc(Op::ADD, 4, 1, 3));                         // 4
  b.emit(abc(Op::SUB, 5, 4, 1));                         // 5
  b.emit(abc(Op::ST_32, 5, 1, 8));                       // 6
  b.emit(abc(Op::RET));                                  // 7
  return b;
}

TEST(MachineQuick, AnIndexAndTheAddAfterItAreOneDispatch) {
  ModuleBuilder b = indexThenAdd(3);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[3].op, vm::quickOpcode(vm::QuickOp::INDEX_ADD));
  EXPECT_EQ(q.code[4].op, Op::ADD);  // stays, for jumps to it
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.countInstructions(true);
  ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
  EXPECT_EQ(loaded(vm, 64 + 8, true), 8);  // element 3 of [1..4], 4 bytes each
  EXPECT_EQ(vm.instructionsExecuted(), 8u);
  // Entering at the ADD adds what r3 holds.
  ModuleBuilder j = indexThenAdd(3, true);
  ASSERT_EQ(bc::verifyModule(j.m), "");
  vm::Machine jv(j.m);
  jv.coldStart();
  ASSERT_TRUE(jv.run(0, 64)) << jv.fault().describe(j.m);
  EXPECT_EQ(loaded(jv, 64 + 8, true), 12);
}

TEST(MachineQuick, AFusedIndexFaultsAtTheIndexAsBefore) {
  for (const int32_t i : {0, 5}) {
    ModuleBuilder b = indexThenAdd(i);
    ASSERT_EQ(bc::verifyModule(b.m), "");
    vm::Machine vm(b.m);
    vm.coldStart();
    ASSERT_FALSE(vm.run(0, 64));
    EXPECT_EQ(vm.fault().kind, bc::FaultKind::IndexOutOfRange);
    EXPECT_EQ(vm.fault().pc, 3u);
    EXPECT_EQ(vm.fault().loc.line, 30u);
  }
}

TEST(MachineQuick, AccessesToAnArrayElementAreQuickenedWithTheArrayInTheEntryCheck) {
  // this->a : ARRAY[1..4] of 8-byte elements at this + 0; i at this + 0 too (only read first).
  ModuleBuilder b(kStatic);
  b.m.indexes.push_back({1, 4, 8});
  b.poke<int32_t>(64, 2);
  b.poke<int32_t>(64 + 8 + 4 + 8, 77);
  b.beginPou("MAIN", 8, 0, 0, bc::PouKind::Program);
  b.emit(abc(Op::LD_I32, 2, 1, 0));     // 0: i
  b.emit(abc(Op::INDEX, 3, 2, 0));      // 1
  b.emit(abc(Op::ADD, 4, 1, 3));        // 2: &a[i]
  b.emit(abc(Op::ADDI, 5, 4, 4));       // 3: &a[i].m (+4)
  b.emit(abc(Op::LD_I32, 6, 5, 8));     // 4: reaches 24 + 4 + 8 + 4 = 40 past this
  b.emit(abc(Op::ST_32, 6, 4, 16));     // 5: reaches 24 + 16 + 4 = 44
  b.emit(asbx(Op::JZ, 6, 0));           // 6: makes 7 a branch target
  b.emit(abc(Op::LD_I32, 7, 4, 0));     // 7: another block: r4 no longer known
  b.emit(abc(Op::RET));                 // 8
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[4].op, vm::quickOpcode(vm::QuickOp::LD_I32));
  EXPECT_EQ(q.code[5].op, vm::quickOpcode(vm::QuickOp::ST_32));
  EXPECT_EQ(q.code[7].op, Op::LD_I32);
  EXPECT_TRUE(q.entry[0].admits(0, b.m.memorySize() - 44));
  EXPECT_FALSE(q.entry[0].admits(0, b.m.memorySize() - 43));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
  EXPECT_EQ(loaded(vm, 64 + 8 + 16, true), 77);
}

TEST(MachineQuick, AStandardFbOfAnArrayIsCalledWithoutTheCheckWithTheArrayInTheEntryCheck) {
  // this->t : ARRAY[0..3] OF R_TRIG (4 bytes each: CLK, Q, M) at this + 8; i at this + 0.
  ModuleBuilder b(kStatic);
  b.m.indexes.push_back({0, 4, 4});
  b.poke<int32_t>(64, 2);
  b.beginPou("MAIN", 6, 0, 0, bc::PouKind::Program);
  b.emit(abc(Op::LD_I32, 2, 1, 0));                                          // 0: i
  b.emit(abc(Op::INDEX, 3, 2, 0));                                           // 1
  b.emit(abc(Op::ADD, 4, 1, 3));                                             // 2
  b.emit(abc(Op::ADDI, 5, 4, 8));                                            // 3: &t[i]
  b.emit(abc(Op::STK_8, 1, 5, 0));                                           // 4: t[i].CLK := TRUE
  b.emit(abx(Op::CALLFB, 5, static_cast<uint32_t>(bc::NativeFb::R_TRIG)));  // 5: reaches 12 + 8 + 3
  b.emit(abc(Op::RET));                                                      // 6
  ASSERT_EQ(bc::verifyModule(b.m), "");
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[4].op, vm::quickOpcode(vm::QuickOp::STK_8));
  EXPECT_EQ(q.code[5].op, vm::quickOpcode(vm::QuickOp::CALLFB));
  EXPECT_TRUE(q.entry[0].admits(0, b.m.memorySize() - 23));
  EXPECT_FALSE(q.entry[0].admits(0, b.m.memorySize() - 22));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 64)) << vm.fault().describe(b.m);
  EXPECT_EQ(vm.memory()[64 + 8 + 2 * 4 + 1], 1);  // t[2].Q: the rising edge
  EXPECT_EQ(vm.memory()[64 + 8 + 1 * 4 + 1], 0);
}

TEST(MachineQuick, AnElementAddressAfterACallOrFromANegativeOffsetStaysChecked) {
  ModuleBuilder b(kStatic);
  b.m.indexes.push_back({0, 4, 8});
  b.beginPou("MAIN", 8, 0, 0, bc::PouKind::Program);
  b.emit(abc(Op::LD_I32, 2, 1, 0));                             // 0
  b.emit(abc(Op::INDEX, 3, 2, 0));                              // 1
  b.emit(abc(Op::ADD, 4, 1, 3));                                // 2
  b.emit(abc(Op::ADDI, 5, 4, static_cast<uint16_t>(-4)));       // 3: before the element
  b.emit(abc(Op::LD_I32, 6, 5, 0));                             // 4: checked
  b.emit(abx(Op::CALLN, 4, static_cast<uint32_t>(bc::Native::Count_) - 1));  // 5: r4 and up rewritten
  b.emit(abc(Op::LD_I32, 6, 4, 0));                             // 6: checked
  b.emit(abc(Op::LD_I32, 6, 3, 0));                             // 7: r3 is an offset, not an address
  b.emit(abc(Op::RET));                                         // 8
  const vm::QuickCode q = vm::quicken(b.m, b.m.memorySize());
  EXPECT_EQ(q.code[4].op, Op::LD_I32);
  EXPECT_EQ(q.code[6].op, Op::LD_I32);
  EXPECT_EQ(q.code[7].op, Op::LD_I32);
  EXPECT_EQ(q.code[0].op, vm::quickOpcode(vm::QuickOp::LD_I32));
}

TEST(MachineQuick, AnEnterWithoutAFrameTheMovAndTheCallAreOneDispatch) {
  ModuleBuilder b = callerAndFb(64);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.countInstructions(true);
  ASSERT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  EXPECT_EQ(loaded(vm, 64 + 12, true), 1);   // FB ran on this = 64: this->[12] := this->[8] + 1
  EXPECT_EQ(vm.instructionsExecuted(), 9u);  // counted as the three instructions it stands for
  // Something between the ENTER and the MOV (a function's argument stored into its frame):
  // ENTER0 alone.
  ModuleBuilder s = callerAndFb(64);
  s.m.code[2] = abc(Op::STK_32, 5, 2, 0);
  s.m.code.insert(s.m.code.begin() + 3, abc(Op::MOV, 3, 5));
  s.m.pous[0].codeSize++;
  s.m.pous[1].codeStart++;
  const vm::QuickCode q = vm::quicken(s.m, s.m.memorySize());
  EXPECT_EQ(q.code[1].op, vm::quickOpcode(vm::QuickOp::ENTER0));
}

TEST(MachineQuick, AFusedCallFaultsAtTheCallAsBefore) {
  ModuleBuilder b = callerAndFb(64);
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.setBudget(0);  // no call left: the watchdog stops the CALL
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, bc::FaultKind::WatchdogBudget);
  EXPECT_EQ(vm.fault().pc, 3u);
  EXPECT_EQ(vm.fault().loc.line, 4u);
  EXPECT_EQ(loaded(vm, 64 + 12, true), 0);
}

}  // namespace
}  // namespace virtcom
