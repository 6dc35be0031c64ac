// The peephole pass (src/lang/st/codegen/peephole.cpp): which comparisons become fused
// compare-and-branch instructions, that a comparison whose result is still read stays as it is,
// and that jump targets and line entries follow the removed instructions. What the fused code
// computes is checked by the golden suite on both backends.
#include "lang/st/codegen/peephole.hpp"

#include <gtest/gtest.h>

#include <string>

#include "bytecode/disassembler.hpp"
#include "bytecode/verifier.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::st {
namespace {

using bc::Instr;
using bc::Op;

// The listing of MAIN of a program whose body is `body` over DINT x, y, UDINT u, BOOL b.
std::string mainListing(const std::string& body) {
  SourceManager sources;
  Diagnostics diags;
  const std::string text = "PROGRAM MAIN\nVAR x, y : DINT; u, w : UDINT; b : BOOL; END_VAR\n" + body + "\nEND_PROGRAM\n";
  auto m = compileProgram({{"main.st", text}}, sources, diags);
  if (!m) return "compile error: " + diags.render(sources);
  for (uint32_t p = 0; p < m->pous.size(); ++p)
    if (m->pous[p].name == "MAIN") return bc::disassemble(*m, p);
  return "no MAIN";
}

bool has(const std::string& listing, const std::string& text) { return listing.find(text) != std::string::npos; }
// An instruction of the listing by its opcode ("  0004  EQK      r2, ..."): not JEQK for EQK.
bool hasOp(const std::string& listing, const std::string& op) { return has(listing, "  " + op + " "); }

TEST(Peephole, ComparisonWithAConstantAndItsJumpBecomeOneInstruction) {
  const std::string l = mainListing("IF x < 10 THEN y := 1; END_IF");
  EXPECT_TRUE(hasOp(l, "JGEK")) << l;  // jump past the THEN branch unless x < 10
  EXPECT_FALSE(hasOp(l, "LTK")) << l;
  EXPECT_FALSE(hasOp(l, "JZ")) << l;
}

TEST(Peephole, RegisterComparisonsFuseWithOperandsSwappedWhenNegated) {
  std::string l = mainListing("WHILE x <> y DO x := x + 1; END_WHILE");
  EXPECT_TRUE(hasOp(l, "JEQ")) << l;  // leave the loop when x = y
  EXPECT_FALSE(hasOp(l, "NE")) << l;
  l = mainListing("IF u <= w THEN b := TRUE; END_IF");
  EXPECT_TRUE(hasOp(l, "JLT_U")) << l;  // skip when w < u
  l = mainListing("FOR x := 1 TO y DO b := NOT b; END_FOR");
  EXPECT_TRUE(hasOp(l, "JLT_I")) << l;  // leave when y < x
  EXPECT_FALSE(hasOp(l, "LE_I")) << l;
}

TEST(Peephole, NotOfABoolBeforeAJumpBecomesTheOppositeJump) {
  const std::string l = mainListing("IF NOT b THEN x := 1; END_IF");
  EXPECT_FALSE(hasOp(l, "LNOT")) << l;
  EXPECT_TRUE(hasOp(l, "JNZ")) << l;
}

TEST(Peephole, CaseLabelsFuse) {
  const std::string l = mainListing("CASE x OF 1: y := 10; 2..5: y := 20; ELSE y := 0; END_CASE");
  EXPECT_TRUE(hasOp(l, "JNEK")) << l;
  EXPECT_FALSE(hasOp(l, "EQK")) << l;
}

// A module with one POU of hand-written code (4 registers), for the pass alone.
bc::Module onePou(std::vector<Instr> code) {
  bc::Module m;
  m.code = std::move(code);
  bc::PouInfo p;
  p.name = "P";
  p.codeSize = static_cast<uint32_t>(m.code.size());
  p.numRegs = 4;
  m.pous.push_back(p);
  return m;
}

TEST(Peephole, AComparisonWhoseResultIsReadLaterStays) {
  // r2 := r3 < 5; if not r2 goto end; r2 is stored at the target: it must keep its value.
  bc::Module m = onePou({Instr::abc(Op::LTK, 2, 3, 5), Instr::asbx(Op::JZ, 2, 1), Instr::abc(Op::STK_8, 1, 1, 0),
                         Instr::abc(Op::ST_8, 2, 1, 0), Instr::abc(Op::RET, 0, 0, 0)});
  optimizePou(m, 0, 0, 4);
  ASSERT_EQ(m.code.size(), 5u);
  EXPECT_EQ(m.code[0].op, Op::LTK);
  EXPECT_EQ(m.code[1].op, Op::JZ);
}

TEST(Peephole, TargetsAndLineEntriesFollowTheRemovedInstructions) {
  // 0: r2 := r3 == 7   1: JZ r2 -> 4   2: STK   3: JMP -> 0 (backward)   4: RET
  bc::Module m = onePou({Instr::abc(Op::EQK, 2, 3, 7), Instr::asbx(Op::JZ, 2, 2), Instr::abc(Op::STK_8, 1, 1, 0),
                         Instr::asbx(Op::JMP, 0, -4), Instr::abc(Op::RET, 0, 0, 0)});
  m.lines = {{0, {0, 1, 1}}, {2, {0, 2, 1}}, {4, {0, 3, 1}}};
  optimizePou(m, 0, 0, 4);
  ASSERT_EQ(m.code.size(), 4u);
  EXPECT_EQ(m.code[0].op, Op::JNEK);
  EXPECT_EQ(bc::branchTarget(0, m.code[0]), 3);  // the RET
  EXPECT_EQ(bc::branchTarget(2, m.code[2]), 0);  // the loop's top
  EXPECT_EQ(m.lines[0].pc, 0u);
  EXPECT_EQ(m.lines[1].pc, 1u);
  EXPECT_EQ(m.lines[2].pc, 3u);
}

TEST(Peephole, AJumpThatIsItselfATargetStays) {
  // 0: r2 := r3 > 1   1: JZ r2 -> 3   2: JMP -> 1   3: RET; the JZ is reached from pc 2 too.
  bc::Module m = onePou({Instr::abc(Op::GTK, 2, 3, 1), Instr::asbx(Op::JZ, 2, 1), Instr::asbx(Op::JMP, 0, -2),
                         Instr::abc(Op::RET, 0, 0, 0)});
  optimizePou(m, 0, 0, 4);
  EXPECT_EQ(m.code.size(), 4u);
  EXPECT_EQ(m.code[0].op, Op::GTK);
}

}  // namespace
}  // namespace virtcom::st
