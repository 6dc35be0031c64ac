// verifyModule: a valid module passes; each kind of malformation is named precisely.
#include <gtest/gtest.h>

#include <functional>

#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"

namespace virtcom {
namespace {

using bc::Op;
using test::abc;
using test::abx;
using test::asbx;
using test::ModuleBuilder;

// MAIN (pou 0) calls F (pou 1); a small valid module to break in one place per test.
ModuleBuilder valid() {
  ModuleBuilder b;
  b.constant(42);
  b.beginPou("MAIN", 8, 0, 0, bc::PouKind::Program);
  b.emit(abx(Op::LDK, 2, 0), 1, 1);                     // pc 0
  b.emit(abx(Op::STA_32, 2, 100));                      // pc 1
  b.emit(abx(Op::ENTER, 4, 1));                         // pc 2
  b.emit(abx(Op::CALL, 4, 1));                          // pc 3
  b.emit(abx(Op::CALLN, 2, static_cast<uint32_t>(bc::Native::STR_LEN)));  // pc 4
  b.emit(asbx(Op::JZ, 2, -3));                          // pc 5 -> 3
  b.emit(abc(Op::LD_BIT, 3, 2, 7));                     // pc 6
  b.emit(abc(Op::SEXT, 3, 3, 16));                      // pc 7
  b.emit(abc(Op::RET));                                 // pc 8
  b.beginPou("F", 4, 16, 512);
  b.emit(abc(Op::ADD, 2, 2, 3), 2, 1, 1);               // pc 9
  b.emit(abx(Op::TRAP, 0, static_cast<uint32_t>(bc::FaultKind::AbstractCall)));  // pc 10
  bc::TypeDesc dint;
  dint.elem = ElemType::Dint;
  dint.name = "DINT";
  dint.size = 4;
  b.m.types.push_back(dint);
  b.m.symbols.push_back({"GVL.x", 0, 100, false});
  return b;
}

std::string verifyWith(const std::function<void(bc::Module&)>& breakIt) {
  ModuleBuilder b = valid();
  breakIt(b.m);
  return bc::verifyModule(b.m);
}

TEST(Verifier, AcceptsValidModule) { EXPECT_EQ(bc::verifyModule(valid().m), ""); }

TEST(Verifier, RejectsRegisterOutsideWindow) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[9] = abc(Op::ADD, 2, 2, 40); }),
            "pou 'F' pc 9: register 40 outside window of 4");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[0] = abx(Op::LDK, 8, 0); }),
            "pou 'MAIN' pc 0: register 8 outside window of 8");
}

TEST(Verifier, RejectsCallAndNativeWindows) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[3] = abx(Op::CALL, 7, 1); }),
            "pou 'MAIN' pc 3: register 8 outside window of 8");
  // STR_REPLACE takes 6 arguments: r4..r9 does not fit in 8 registers.
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[4] = abx(Op::CALLN, 4, static_cast<uint32_t>(bc::Native::STR_REPLACE)); }),
            "pou 'MAIN' pc 4: register 9 outside window of 8");
}

TEST(Verifier, RejectsBadIndices) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[0] = abx(Op::LDK, 2, 1); }), "pou 'MAIN' pc 0: constant 1 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[3] = abx(Op::CALL, 4, 2); }), "pou 'MAIN' pc 3: pou index 2 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[2] = abx(Op::ENTER, 4, 99); }), "pou 'MAIN' pc 2: pou index 99 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[4] = abx(Op::CALLN, 2, 999); }),
            "pou 'MAIN' pc 4: native index 999 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[10] = abx(Op::TRAP, 0, 0); }), "pou 'F' pc 10: trap kind 0 unknown");
}

TEST(Verifier, RejectsBadOpcode) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[1].op = static_cast<Op>(250); }), "pou 'MAIN' pc 1: invalid opcode 250");
}

TEST(Verifier, RejectsAbsoluteAddresses) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[1] = abx(Op::STA_32, 2, 4); }),
            "pou 'MAIN' pc 1: absolute address 4 outside static memory");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[1] = abx(Op::LDA_64, 2, 1020); }),
            "pou 'MAIN' pc 1: absolute address 1020 outside static memory");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[1] = abx(Op::STA_32, 2, 1020); }), "");
}

TEST(Verifier, RejectsJumpsOutsidePou) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[5] = asbx(Op::JZ, 2, 3); }),
            "pou 'MAIN' pc 5: jump target 9 outside the pou");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[5] = asbx(Op::JMP, 0, -7); }),
            "pou 'MAIN' pc 5: jump target -1 outside the pou");
}

TEST(Verifier, RejectsImmediates) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[6] = abc(Op::LD_BIT, 3, 2, 8); }), "pou 'MAIN' pc 6: bit index 8 above 7");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::SEXT, 3, 3, 65); }),
            "pou 'MAIN' pc 7: bit count 65 not in 1..64");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::MODK, 3, 3, 0); }), "pou 'MAIN' pc 7: divisor 0");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::DIVK, 3, 3, 0); }), "pou 'MAIN' pc 7: divisor 0");
  // STK_*: A is a value, B still a register of the window.
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::STK_32, 0xffff, 3, 4); }), "");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::STK_32, 1, 8, 4); }),
            "pou 'MAIN' pc 7: register 8 outside window of 8");
  EXPECT_EQ(verifyWith([](bc::Module& m) {
              m.code[7] = abx(Op::CALLFB, 3, static_cast<uint32_t>(bc::NativeFb::Count_));
            }),
            "pou 'MAIN' pc 7: native FB index 10 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::INDEX, 3, 3, 0); }),
            "pou 'MAIN' pc 7: index descriptor 0 out of range");
  EXPECT_EQ(verifyWith([](bc::Module& m) {
              m.indexes.push_back({1, 8, 2});
              m.code[7] = abc(Op::INDEX, 3, 3, 0);
            }),
            "");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abx(Op::CALLFB, 8, 0); }),
            "pou 'MAIN' pc 7: register 8 outside window of 8");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.code[7] = abc(Op::EQK, 8, 3, 4); }),
            "pou 'MAIN' pc 7: register 8 outside window of 8");
}

TEST(Verifier, RejectsPouLayout) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.pous[1].codeSize = 5; }), "pou 'F': code range outside the code");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.pous[1].codeSize = 1; }), "pou 'F': code does not end with RET, JMP or TRAP");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.pous[1].frameTemplate = 1020; }), "pou 'F': frame template outside static memory");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.pous[0].numRegs = 1; }), "pou 'MAIN': fewer than 2 registers");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.pous[0].numRegs = 9000; m.registerStackSize = 100; }),
            "pou 'MAIN': register window larger than the register stack");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.initPou = 7; }), "init pou index out of range");
}

TEST(Verifier, RejectsImageAndTables) {
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.initialImage.resize(10); }), "initial image has 10 bytes, static size is 1024");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.lines.push_back({3, {0, 1, 1}}); }), "line table not sorted by pc");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.lines[0].loc.fileId = 9; }), "line entry 0 names unknown file 9");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.symbols[0].address = 1022; }), "symbol 'GVL.x' outside static memory");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.symbols[0].type = 5; }), "symbol 'GVL.x' has an invalid type");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.types[0].size = 2; }), "type 0 'DINT': size does not match its elementary type");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.programs.push_back({"MAIN", 3, 200}); }), "program 'MAIN' has an invalid pou");
  EXPECT_EQ(verifyWith([](bc::Module& m) { m.tasks.push_back({"T", 1, 0, {0}}); }), "task 'T' names an invalid program");
  EXPECT_EQ(verifyWith([](bc::Module& m) {
              bc::TypeDesc s;
              s.kind = bc::TypeKind::Struct;
              s.name = "S";
              s.size = 2;
              bc::Field a;
              a.name = "a";
              a.type = 0;
              s.fields.push_back(a);
              m.types.push_back(s);
            }),
            "type 1 'S': field 'a' outside the struct");
  EXPECT_EQ(verifyWith([](bc::Module& m) {
              bc::TypeDesc s;
              s.kind = bc::TypeKind::Struct;
              s.name = "P";
              s.size = 2;
              bc::Field located;
              located.name = "sensor";
              located.type = 0;
              located.offset = 1022;  // a located member's offset is an absolute address
              located.absolute = true;
              s.fields.push_back(located);
              m.types.push_back(s);
              m.types.back().fields.back().offset = 1000;
              std::string ok = bc::verifyModule(m);
              EXPECT_EQ(ok, "");
              m.types.back().fields.back().offset = 1022;
            }),
            "type 1 'P': field 'sensor' outside the static memory");
}

}  // namespace
}  // namespace virtcom
