// Loop-invariant constants (src/lang/st/codegen/loop_constants.cpp, run by optimizePou): which
// constant loads leave a loop to be loaded once before it, and which stay because their register
// holds something else in the loop, is read before them, or the loop is entered elsewhere. What
// the code computes is checked by the golden suite on both backends
// (tests/golden/st/statements/loop_constants.st).
#include <gtest/gtest.h>

#include "lang/st/codegen/peephole.hpp"

namespace virtcom::st {
namespace {

using bc::Instr;
using bc::Op;

// One POU of hand-written code (8 registers), optimised (its register count the one optimizePou
// returns); a line entry at each of `lines`.
bc::Module optimised(std::vector<Instr> code, std::vector<uint32_t> lines = {}) {
  bc::Module m;
  m.code = std::move(code);
  for (uint32_t pc : lines) m.lines.push_back({pc, {}});
  bc::PouInfo p;
  p.name = "P";
  p.codeSize = static_cast<uint32_t>(m.code.size());
  p.numRegs = 8;
  m.pous.push_back(p);
  m.pous[0].numRegs = optimizePou(m, 0, 0, 8);
  return m;
}

const Instr kRet = Instr::abc(Op::RET, 0, 0, 0);
const Instr kLoad7 = Instr::asbx(Op::LDI, 3, 7);
// x := x + r3 (x in r2, stored at offset 0), then the loop's test: back to pc `head` (the test
// itself at pc `at`) while x < 100.
std::vector<Instr> addAndTest(uint32_t at, uint32_t head) {
  return {Instr::abc(Op::ADD, 2, 2, 3), Instr::abc(Op::ST_32, 2, 1, 0), Instr::abc(Op::LTK, 4, 2, 100),
          Instr::asbx(Op::JNZ, 4, static_cast<int32_t>(head) - static_cast<int32_t>(at + 3) - 1)};
}
std::vector<Instr> concat(std::vector<Instr> a, const std::vector<Instr>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
// The target of the last backward branch of `m`.
int64_t loopHead(const bc::Module& m) {
  for (uint32_t k = static_cast<uint32_t>(m.code.size()); k-- > 0;)
    if (bc::isBranch(m.code[k].op) && bc::branchTarget(k, m.code[k]) <= k) return bc::branchTarget(k, m.code[k]);
  return -1;
}

TEST(LoopConstants, AConstantIsLoadedOnceBeforeTheLoop) {
  const bc::Module m = optimised(concat({Instr::abc(Op::LD_I32, 2, 1, 0), kLoad7}, concat(addAndTest(2, 1), {kRet})), {1, 2});
  ASSERT_EQ(m.code[1].op, Op::LDI);
  EXPECT_EQ(loopHead(m), 2);  // the loop starts with the ADD now
  EXPECT_EQ(m.code[2].op, Op::ADD);
  // The line entry of the moved load now marks the next instruction that stayed.
  EXPECT_EQ(m.lines[0].pc, 2u);
  EXPECT_EQ(m.lines[1].pc, 2u);
}

TEST(LoopConstants, AConstantWhoseRegisterHoldsAnotherValueInTheLoopGetsARegisterOfItsOwn) {
  const bc::Module m = optimised(concat({Instr::abc(Op::LD_I32, 2, 1, 0), kLoad7, Instr::abc(Op::ADD, 2, 2, 3),
                                         Instr::abc(Op::LD_I32, 3, 1, 4)},
                                        concat(addAndTest(4, 1), {kRet})));
  EXPECT_EQ(loopHead(m), 2);
  ASSERT_EQ(m.code[1].op, Op::LDI);
  EXPECT_EQ(m.code[1].a, 8);  // the first register above the POU's 8
  EXPECT_EQ(m.code[2].c, 8);  // the ADD reads it
  EXPECT_EQ(m.code[4].c, 3);  // the other ADD still reads the loaded r3
  EXPECT_EQ(m.pous[0].numRegs, 9);
}

TEST(LoopConstants, AConstantReadInAnotherBasicBlockWhereItsRegisterHoldsAnotherValueStays) {
  // The ADD at 3 reads the constant after the JZ; the one at 5 reads the value loaded at 4.
  const bc::Module m = optimised({Instr::abc(Op::LD_I32, 2, 1, 0), kLoad7, Instr::asbx(Op::JZ, 2, 1), Instr::abc(Op::ADD, 2, 2, 3),
                                  Instr::abc(Op::LD_I32, 3, 1, 4), Instr::abc(Op::ADD, 2, 2, 3), Instr::abc(Op::ST_32, 2, 1, 0),
                                  Instr::abc(Op::LTK, 4, 2, 100), Instr::asbx(Op::JNZ, 4, -8), kRet});
  EXPECT_EQ(loopHead(m), 1);
  EXPECT_EQ(m.code[1].op, Op::LDI);
  EXPECT_EQ(m.pous[0].numRegs, 8);
}

TEST(LoopConstants, AConstantWhoseRegisterIsReadBeforeItInTheLoopStays) {
  // r3 is 5 in the first iteration, 7 in the others.
  const bc::Module m = optimised(
      concat({Instr::abc(Op::LD_I32, 2, 1, 0), Instr::asbx(Op::LDI, 3, 5), Instr::abc(Op::ADD, 2, 2, 3), kLoad7},
             {Instr::abc(Op::ST_32, 2, 1, 0), Instr::abc(Op::LTK, 4, 2, 100), Instr::asbx(Op::JNZ, 4, -5), kRet}));
  EXPECT_EQ(loopHead(m), 2);
  EXPECT_EQ(m.code[3].op, Op::LDI);
}

TEST(LoopConstants, AConstantACallMayOverwriteStays) {
  // A call's register window starts at r3: the callee may write it.
  const bc::Module m = optimised(concat({Instr::abc(Op::LD_I32, 2, 1, 0), kLoad7, Instr::abx(Op::CALL, 3, 0)},
                                        concat(addAndTest(3, 1), {kRet})));
  EXPECT_EQ(loopHead(m), 1);
  EXPECT_EQ(m.code[1].op, Op::LDI);
}

TEST(LoopConstants, ALoopEnteredOtherThanAtItsHeadKeepsItsConstants) {
  // The JZ jumps from before the loop to its ADD, past the load.
  const bc::Module m = optimised(concat({Instr::abc(Op::LD_I32, 2, 1, 0), Instr::asbx(Op::JZ, 2, 1), kLoad7},
                                        concat(addAndTest(3, 2), {kRet})));
  EXPECT_EQ(loopHead(m), 2);
  EXPECT_EQ(m.code[2].op, Op::LDI);
}

TEST(LoopConstants, ARepeatOfTheSameConstantInTheLoopGoesToo) {
  const bc::Module m = optimised(concat({Instr::abc(Op::LD_I32, 2, 1, 0), kLoad7, Instr::abc(Op::ADD, 2, 2, 3), kLoad7},
                                        concat(addAndTest(4, 1), {kRet})));
  ASSERT_EQ(m.code[1].op, Op::LDI);
  EXPECT_EQ(loopHead(m), 2);
  for (size_t k = 2; k < m.code.size(); ++k) EXPECT_NE(m.code[k].op, Op::LDI) << k;
}

}  // namespace
}  // namespace virtcom::st
