// Calls, frames, faults with locations, the watchdog.
#include <gtest/gtest.h>

#include <cstring>

#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

using bc::FaultKind;
using bc::Op;
using test::abc;
using test::abx;
using test::asbx;
using test::ModuleBuilder;

int64_t rd64(const vm::Machine& vm, uint32_t a) {
  int64_t v;
  std::memcpy(&v, vm.memory() + a, 8);
  return v;
}

// MAIN calls ADD3(a, b, c) whose frame is [a, b, c, result] (4 x i64) with template
// values at 512 = {0, 0, 100, 0}: ADD3(1, 2) = 1 + 2 + 100 (c defaulted by the template).
ModuleBuilder callModule() {
  ModuleBuilder b;
  b.poke<int64_t>(512 + 16, 100);
  const uint32_t add3 = 1;
  b.beginPou("MAIN", 8, 0, 0, bc::PouKind::Program);
  b.emit(abx(Op::ENTER, 4, add3), 3);
  b.emit(asbx(Op::LDI, 6, 1));
  b.emit(abc(Op::ST_64, 6, 4, 0));
  b.emit(asbx(Op::LDI, 6, 2));
  b.emit(abc(Op::ST_64, 6, 4, 8));
  b.emit(asbx(Op::LDI, 5, 0));
  b.emit(abx(Op::CALL, 4, add3));
  b.emit(abc(Op::LD_64, 6, 4, 24), 4);
  b.emit(abx(Op::STA_64, 6, 16));
  b.emit(abc(Op::RET));
  b.beginPou("ADD3", 5, 32, 512);
  b.emit(abc(Op::LD_64, 2, 0, 0), 10, 3, 1);
  b.emit(abc(Op::LD_64, 3, 0, 8));
  b.emit(abc(Op::ADD, 2, 2, 3));
  b.emit(abc(Op::LD_64, 3, 0, 16));
  b.emit(abc(Op::ADD, 2, 2, 3));
  b.emit(abc(Op::ST_64, 2, 0, 24));
  b.emit(abc(Op::RET));
  return b;
}

TEST(MachineCall, CallWithFrameTemplate) {
  ModuleBuilder b = callModule();
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  const uint32_t sp0 = vm.stackPointer();
  EXPECT_EQ(sp0, b.m.staticSize);
  ASSERT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  EXPECT_EQ(rd64(vm, 16), 103);
  EXPECT_EQ(vm.stackPointer(), sp0);
  // A second run sees a fresh frame from the template again.
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_EQ(rd64(vm, 16), 103);
}

TEST(MachineCall, TopLevelFrameComesFromTemplate) {
  ModuleBuilder b;
  b.poke<int32_t>(600, 77);
  b.beginPou("F", 4, 8, 600);
  b.emit(abc(Op::LD_I32, 2, 0, 0));
  b.emit(abx(Op::STA_32, 2, 16));
  b.emit(abc(Op::ST_32, 2, 1, 0));  // *this = 77
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 700));
  EXPECT_EQ(rd64(vm, 16) & 0xffffffff, 77);
  EXPECT_EQ(vm.memory()[700], 77);
}

// MAIN -> A -> B where B divides by zero: the fault names B's line and both call sites.
ModuleBuilder nestedFaultModule() {
  ModuleBuilder b;
  b.beginPou("MAIN", 6, 0, 0, bc::PouKind::Program);      // pou 0
  b.emit(abx(Op::ENTER, 2, 1), 5, 1);
  b.emit(abx(Op::CALL, 2, 1), 6, 3);                       // pc 1
  b.emit(abc(Op::RET));
  b.beginPou("A", 6, 8, 512);                                 // pou 1
  b.emit(abx(Op::ENTER, 3, 2), 2, 1, 1);
  b.emit(abx(Op::CALL, 3, 2), 3, 1, 1);                    // pc 4
  b.emit(abc(Op::RET));
  b.beginPou("B", 5, 8, 512);                                 // pou 2
  b.emit(asbx(Op::LDI, 2, 7), 12, 1);
  b.emit(asbx(Op::LDI, 3, 0));
  b.emit(abc(Op::DIV_I, 4, 2, 3), 12, 5);                  // pc 8
  b.emit(abc(Op::RET));
  return b;
}

TEST(MachineCall, FaultInNestedCallReportsStack) {
  ModuleBuilder b = nestedFaultModule();
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  const uint32_t sp0 = vm.stackPointer();
  ASSERT_FALSE(vm.run(0, 0));
  const vm::FaultInfo& f = vm.fault();
  EXPECT_EQ(f.kind, FaultKind::DivisionByZero);
  EXPECT_EQ(f.pc, 8u);
  EXPECT_EQ(f.loc.line, 12u);
  EXPECT_EQ(f.loc.col, 5u);
  ASSERT_EQ(f.callStack.size(), 2u);
  EXPECT_EQ(f.callStack[0], 4u);
  EXPECT_EQ(f.callStack[1], 1u);
  EXPECT_EQ(f.describe(b.m),
            "division by zero at MAIN.st:12:5\n"
            "  called from FB_x.st:3:1 (in A)\n"
            "  called from MAIN.st:6:3 (in MAIN)");
  EXPECT_EQ(vm.stackPointer(), sp0);
  // The machine stays usable after a fault.
  ASSERT_FALSE(vm.run(2, 0));
  EXPECT_TRUE(vm.fault().callStack.empty());
}

TEST(MachineCall, FaultWithoutLineNamesPc) {
  ModuleBuilder b;
  b.beginPou("MAIN", 4);
  b.emit(asbx(Op::LDI, 2, 0));
  b.emit(abc(Op::MOD_U, 3, 2, 2));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().describe(b.m), "division by zero at pc 1 (in MAIN)");
}

TEST(MachineCall, DivisionFaults) {
  for (Op op : {Op::DIV_I, Op::MOD_I, Op::DIV_U, Op::MOD_U}) {
    ModuleBuilder b;
    b.beginPou("MAIN", 4);
    b.emit(asbx(Op::LDI, 2, 5));
    b.emit(abc(op, 3, 2, 3), 7, 9);
    b.emit(abc(Op::RET));
    vm::Machine vm(b.m);
    vm.coldStart();
    ASSERT_FALSE(vm.run(0, 0));
    EXPECT_EQ(vm.fault().kind, FaultKind::DivisionByZero) << bc::opName(op);
    EXPECT_EQ(vm.fault().pc, 1u);
  }
}

TEST(MachineCall, InvalidPointerFaults) {
  struct Case { bc::Instr ins; int32_t base; };
  for (Case c : {Case{abc(Op::LD_I32, 2, 3, 0), 0}, Case{abc(Op::LD_I32, 2, 3, 15), 0},
                 Case{abc(Op::ST_8, 2, 3, 0), 8}, Case{abc(Op::LD_64, 2, 3, 0), 1024 + 4096 - 7},
                 Case{abc(Op::LD_BIT, 2, 3, 0), 1024 + 4096}, Case{abc(Op::ST_BIT, 2, 3, 1), 4},
                 Case{abc(Op::ST_64, 2, 3, 0xffff), -100}, Case{abc(Op::COPY, 3, 2, 2), 8}}) {
    ModuleBuilder b;
    b.beginPou("MAIN", 4);
    b.emit(asbx(Op::LDI, 3, c.base));
    b.emit(asbx(Op::LDI, 2, 16));
    b.emit(c.ins, 4, 2);
    b.emit(abc(Op::RET));
    vm::Machine vm(b.m);
    vm.coldStart();
    ASSERT_FALSE(vm.run(0, 0)) << bc::opName(c.ins.op) << " base " << c.base;
    EXPECT_EQ(vm.fault().kind, FaultKind::InvalidPointer);
    EXPECT_EQ(vm.fault().pc, 2u);
    EXPECT_EQ(vm.fault().loc.line, 4u);
  }
}

TEST(MachineCall, AccessAtTheLastValidByte) {
  ModuleBuilder b;
  b.beginPou("MAIN", 4);
  b.emit(asbx(Op::LDI, 3, 1024 + 4096 - 8));
  b.emit(asbx(Op::LDI, 2, -1));
  b.emit(abc(Op::ST_64, 2, 3, 0));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  EXPECT_TRUE(vm.run(0, 0));
}

TEST(MachineCall, BoundFault) {
  ModuleBuilder b;
  b.beginPou("MAIN", 4);
  b.m.indexes.push_back({0, 10, 4});
  b.emit(asbx(Op::LDI, 2, -1));
  b.emit(abc(Op::INDEX, 3, 2, 0), 9, 1);
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::IndexOutOfRange);
  EXPECT_EQ(vm.fault().describe(b.m), "array index out of range at MAIN.st:9:1");
}

TEST(MachineCall, TrapCarriesItsKind) {
  ModuleBuilder b;
  b.beginPou("MAIN", 2);
  b.emit(abx(Op::TRAP, 0, static_cast<uint32_t>(FaultKind::InvalidEnumValue)), 2, 1);
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::InvalidEnumValue);
  EXPECT_EQ(vm.fault().pc, 0u);
}

TEST(MachineCall, WatchdogStopsEndlessLoop) {
  ModuleBuilder b;
  b.beginPou("MAIN", 2);
  b.emit(abc(Op::NOP), 1, 1);
  b.emit(asbx(Op::JMP, 0, -2), 2, 1);
  vm::Machine vm(b.m);
  vm.countInstructions(true);
  vm.coldStart();
  vm.setBudget(1000);
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::WatchdogBudget);
  EXPECT_EQ(vm.fault().pc, 1u);
  EXPECT_EQ(vm.fault().loc.line, 2u);
  EXPECT_EQ(vm.instructionsExecuted(), 2002u);
  // The budget is per run.
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.instructionsExecuted(), 4004u);
}

TEST(MachineCall, BudgetCountsCalls) {
  ModuleBuilder b = callModule();
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.setBudget(0);
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::WatchdogBudget);
  EXPECT_EQ(vm.fault().pc, 6u);
  vm.setBudget(1);
  EXPECT_TRUE(vm.run(0, 0));
}

TEST(MachineCall, RecursionOverflowsCallDepth) {
  ModuleBuilder b;
  b.m.maxCallDepth = 10;
  b.beginPou("R", 4);
  b.emit(abx(Op::ENTER, 2, 0), 1, 1);
  b.emit(abx(Op::CALL, 2, 0), 1, 1);
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::StackOverflow);
  EXPECT_EQ(vm.fault().callStack.size(), 10u);
  EXPECT_EQ(vm.stackPointer(), b.m.staticSize);
}

TEST(MachineCall, RecursionOverflowsMemoryStack) {
  ModuleBuilder b;
  b.beginPou("R", 4, 1000);
  b.emit(abx(Op::ENTER, 2, 0));
  b.emit(abx(Op::CALL, 2, 0));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::StackOverflow);
  EXPECT_EQ(vm.fault().pc, 0u);  // the ENTER that did not fit
}

TEST(MachineCall, RecursionOverflowsRegisterStack) {
  ModuleBuilder b;
  b.m.registerStackSize = 64;
  b.beginPou("R", 8);
  b.emit(abx(Op::ENTER, 6, 0));
  b.emit(abx(Op::CALL, 6, 0));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_FALSE(vm.run(0, 0));
  EXPECT_EQ(vm.fault().kind, FaultKind::StackOverflow);
  EXPECT_EQ(vm.fault().pc, 1u);
  EXPECT_EQ(vm.fault().callStack.size(), 9u);  // windows at 0, 6, ..., 54; 60 + 8 > 64
}

TEST(MachineCall, ColdStartRunsInitPouAndResetsMemory) {
  ModuleBuilder b;
  b.poke<uint8_t>(100, 5);
  b.beginPou("INIT", 4, 0, 0, bc::PouKind::Init);
  b.emit(asbx(Op::LDI, 2, 9));
  b.emit(abx(Op::STA_8, 2, 101));
  b.emit(abc(Op::RET));
  b.m.initPou = 0;
  vm::Machine vm(b.m);
  vm.memory()[100] = 1;
  vm.memory()[2000] = 1;
  ASSERT_TRUE(vm.coldStart());
  EXPECT_EQ(vm.memory()[100], 5);
  EXPECT_EQ(vm.memory()[101], 9);
  EXPECT_EQ(vm.memory()[2000], 0);
}

}  // namespace
}  // namespace virtcom
