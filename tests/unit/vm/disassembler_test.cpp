// The disassembler's text format (compiler golden tests depend on it).
#include <gtest/gtest.h>

#include "bytecode/disassembler.hpp"
#include "test_module_builder.hpp"

namespace virtcom {
namespace {

using bc::Op;
using test::abc;
using test::abx;
using test::asbx;
using test::ModuleBuilder;

TEST(Disassembler, ListsAPou) {
  ModuleBuilder b;
  b.constant(7);
  b.beginPou("MAIN", 8, 0, 0, bc::PouKind::Program);
  b.emit(abx(Op::LDK, 2, 0), 3, 1);
  b.emit(asbx(Op::LDI, 3, -5));
  b.emit(abc(Op::ADD, 3, 4, 5), 12, 5);
  b.emit(abc(Op::ADDI, 3, 3, static_cast<uint16_t>(-1)));
  b.emit(abc(Op::LD_I16, 2, 1, 24));
  b.emit(abc(Op::STK_16, static_cast<uint16_t>(-7), 1, 26));
  b.emit(abc(Op::LTK, 4, 2, static_cast<uint16_t>(-1)));
  b.emit(abc(Op::INDEX, 4, 2, 3));
  b.emit(abx(Op::STA_32, 2, 100));
  b.emit(asbx(Op::JZ, 2, -3));
  b.emit(abx(Op::ENTER, 4, 1), 13, 3);
  b.emit(abx(Op::CALL, 4, 1));
  b.emit(abx(Op::CALLN, 2, static_cast<uint32_t>(bc::Native::STR_CONCAT)));
  b.emit(abx(Op::CALLFB, 1, static_cast<uint32_t>(bc::NativeFb::CTUD)));
  b.emit(abx(Op::TRAP, 0, static_cast<uint32_t>(bc::FaultKind::InvalidEnumValue)));
  b.emit(abc(Op::RET), 20, 1);
  b.beginPou("FB_Motor.Start", 4, 16, 512, bc::PouKind::Method);
  b.emit(abc(Op::RET), 2, 1, 1);
  EXPECT_EQ(bc::disassemble(b.m, 0),
            "MAIN (Program, 8 registers, frame 0 bytes @0)\n"
            "  0000  LDK      r2, k0        ; MAIN.st:3:1\n"
            "  0001  LDI      r3, -5\n"
            "  0002  ADD      r3, r4, r5    ; MAIN.st:12:5\n"
            "  0003  ADDI     r3, r3, -1\n"
            "  0004  LD_I16   r2, r1, 24\n"
            "  0005  STK_16   -7, r1, 26\n"
            "  0006  LTK      r4, r2, -1\n"
            "  0007  INDEX    r4, r2, x3\n"
            "  0008  STA_32   r2, @100\n"
            "  0009  JZ       r2, 0007\n"
            "  0010  ENTER    r4, FB_Motor.Start ; MAIN.st:13:3\n"
            "  0011  CALL     r4, FB_Motor.Start\n"
            "  0012  CALLN    r2, STR_CONCAT\n"
            "  0013  CALLFB   r1, CTUD\n"
            "  0014  TRAP     6 (invalid enum value)\n"
            "  0015  RET                    ; MAIN.st:20:1\n");
  EXPECT_EQ(bc::disassemble(b.m, 1),
            "FB_Motor.Start (Method, 4 registers, frame 16 bytes @512)\n"
            "  0016  RET                    ; FB_x.st:2:1\n");
  EXPECT_EQ(bc::disassemble(b.m, 2), "");
}

TEST(Disassembler, FusedBranchesShowTheirTargetLast) {
  ModuleBuilder b;
  b.beginPou("MAIN", 8);
  b.emit(abc(Op::JLT_I, 2, 3, 1));                                         // register form: offset in C
  b.emit(abc(Op::JGEK, 4, static_cast<uint16_t>(-2), static_cast<uint16_t>(-100)));  // constant form: offset in B
  b.emit(abc(Op::RET));
  EXPECT_EQ(bc::disassembleInstruction(b.m, 0), "JLT_I    r2, r3, 0002");
  EXPECT_EQ(bc::disassembleInstruction(b.m, 1), "JGEK     r4, -100, 0000");
}

TEST(Disassembler, ShowsBadOperandsWithoutFollowingThem) {
  ModuleBuilder b;
  b.beginPou("MAIN", 2);
  b.emit(abx(Op::CALL, 0, 77));
  b.emit(abx(Op::CALLN, 0, 9999));
  b.emit(abc(Op::RET));
  b.m.code.push_back(abc(static_cast<Op>(200), 0));
  b.m.pous[0].codeSize++;
  EXPECT_EQ(bc::disassembleInstruction(b.m, 0), "CALL     r0, pou#77");
  EXPECT_EQ(bc::disassembleInstruction(b.m, 1), "CALLN    r0, native#9999");
  EXPECT_EQ(bc::disassembleInstruction(b.m, 3), "??? 200");
  EXPECT_EQ(bc::disassembleInstruction(b.m, 4), "?");
}

}  // namespace
}  // namespace virtcom

namespace virtcom {
namespace {

TEST(ModuleLookup, LocationOfAndPouAt) {
  test::ModuleBuilder b;
  b.beginPou("MAIN", 2);
  b.emit(test::abc(bc::Op::NOP));                      // pc 0: before any line entry
  b.emit(test::abc(bc::Op::NOP), 4, 2);                // pc 1
  b.emit(test::abc(bc::Op::RET));                      // pc 2: still line 4
  b.beginPou("F", 2);
  b.emit(test::abc(bc::Op::NOP));                      // pc 3: F has no entry yet
  b.emit(test::abc(bc::Op::RET), 9, 1, 1);             // pc 4
  EXPECT_EQ(b.m.locationOf(0).line, 0u);
  EXPECT_EQ(b.m.locationOf(1).line, 4u);
  EXPECT_EQ(b.m.locationOf(2).col, 2u);
  EXPECT_EQ(b.m.locationOf(3).line, 0u);
  EXPECT_EQ(b.m.locationOf(4).fileId, 1u);
  EXPECT_EQ(b.m.pouAt(2), 0u);
  EXPECT_EQ(b.m.pouAt(3), 1u);
  EXPECT_EQ(b.m.pouAt(5), bc::Module::kNoPou);
}

}  // namespace
}  // namespace virtcom
