// The load forwarding pass (src/lang/st/codegen/load_forwarding.cpp, run by optimizePou): which
// repeated loads are served from the register that already holds the location, and which writes,
// calls and joins make the next load read memory again. What the code computes is checked by the
// golden suite on both backends (tests/golden/st/statements/for_reloads.st, reused_values.st, store_reloads.st).
#include <gtest/gtest.h>

#include <string>

#include "bytecode/disassembler.hpp"
#include "lang/st/codegen/peephole.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::st {
namespace {

using bc::Instr;
using bc::Op;

// A module with one POU of hand-written code (8 registers) and array shapes `indexes`, optimised.
bc::Module optimised(std::vector<Instr> code, std::vector<bc::IndexDesc> indexes = {}) {
  bc::Module m;
  m.code = std::move(code);
  m.indexes = std::move(indexes);
  bc::PouInfo p;
  p.name = "P";
  p.codeSize = static_cast<uint32_t>(m.code.size());
  p.numRegs = 8;
  m.pous.push_back(p);
  optimizePou(m, 0, 0, 8);
  return m;
}

Instr ld(uint16_t into, uint16_t offset) { return Instr::abc(Op::LD_I32, into, 1, offset); }
const Instr kRet = Instr::abc(Op::RET, 0, 0, 0);

TEST(LoadForwarding, ASecondLoadOfTheSameLocationReadsTheFirstRegister) {
  const bc::Module m = optimised({ld(2, 0), ld(3, 0), Instr::abc(Op::ADD, 4, 2, 3), Instr::abc(Op::ST_32, 4, 1, 8), kRet});
  ASSERT_EQ(m.code.size(), 4u);
  EXPECT_EQ(m.code[1].op, Op::ADD);
  EXPECT_EQ(m.code[1].b, 2);
  EXPECT_EQ(m.code[1].c, 2);
}

TEST(LoadForwarding, AStoreThatMayOverlapMakesTheLoadReadMemory) {
  const auto between = [](Instr store) {
    return optimised({ld(2, 0), store, ld(3, 0), Instr::abc(Op::ADD, 4, 2, 3), Instr::abc(Op::ST_32, 4, 1, 8), kRet})
        .code.size();
  };
  EXPECT_EQ(between(Instr::abc(Op::ST_8, 5, 1, 3)), 6u);   // the last byte of the location
  EXPECT_EQ(between(Instr::abc(Op::ST_32, 5, 6, 0)), 6u);  // another base may point anywhere
  EXPECT_EQ(between(Instr::abx(Op::STA_32, 5, 64)), 6u);   // so may an absolute address
  EXPECT_EQ(between(Instr::abc(Op::COPY, 5, 6, 7)), 6u);   // a block copy
  EXPECT_EQ(between(Instr::abc(Op::ST_32, 5, 1, 4)), 5u);  // next to it: the load goes
}

// A SEXT/ZEXT of a value already in that form, and a MOV, become a renaming of their source; an
// extension that changes the value stays (statements/widenings.st checks the results).
TEST(LoadForwarding, ARedundantExtensionOrACopyReadsItsSource) {
  const auto kept = [](Instr copy) {
    return optimised({Instr::abc(Op::LD_I16, 2, 1, 0), copy, Instr::abc(Op::ST_32, 3, 1, 8), kRet}).code;
  };
  const std::vector<Instr> widened = kept(Instr::abc(Op::SEXT, 3, 2, 32));
  ASSERT_EQ(widened.size(), 3u);
  EXPECT_EQ(widened[1].a, 2);
  EXPECT_EQ(kept(Instr::abc(Op::SEXT, 3, 2, 16)).size(), 3u);  // an INT is its 16-bit sign-extension
  EXPECT_EQ(kept(Instr::abc(Op::MOV, 3, 2, 0)).size(), 3u);
  EXPECT_EQ(kept(Instr::abc(Op::SEXT, 3, 2, 8)).size(), 4u);   // INT_TO_SINT changes it
  EXPECT_EQ(kept(Instr::abc(Op::ZEXT, 3, 2, 32)).size(), 4u);  // a negative INT as a UDINT
}

TEST(LoadForwarding, ARepeatedComputationReadsTheFirstResult) {
  const bc::Module m = optimised({Instr::asbx(Op::LDI, 2, 7), Instr::asbx(Op::LDI, 3, 7), Instr::abc(Op::ADD, 4, 2, 3),
                                  Instr::abc(Op::ST_32, 4, 1, 0), kRet});
  ASSERT_EQ(m.code.size(), 4u);
  EXPECT_EQ(m.code[1].b, 2);
  EXPECT_EQ(m.code[1].c, 2);
}

TEST(LoadForwarding, AStoreIntoAnArrayElementKeepsWhatIsOutsideTheArray) {
  // ARRAY[0..3] OF WORD at r1 + 0 (x0: 4 elements of 2 bytes), i at r1 + 10: a[i] := v, then
  // load the WORD at `offset` again.
  const auto reloads = [](uint16_t offset) {
    const Instr ld16 = Instr::abc(Op::LD_U16, 2, 1, offset);
    Instr again = ld16;
    again.a = 6;
    return optimised({ld16, Instr::abc(Op::LD_I16, 3, 1, 10), Instr::abc(Op::INDEX, 4, 3, 0),
                      Instr::abc(Op::ADD, 5, 1, 4), Instr::abc(Op::ST_16, 2, 5, 0), again,
                      Instr::abc(Op::ST_16, 6, 1, 12), kRet},
                     {{0, 4, 2}})
        .code.size();
  };
  EXPECT_EQ(reloads(8), 7u);  // just past the last element: served from r2
  EXPECT_EQ(reloads(6), 8u);  // the last element: read again
}

TEST(LoadForwarding, AStoreIntoAMemberOfAnArrayElementKeepsWhatIsOutsideTheArrayOfMembers) {
  // ARRAY[0..3] of an 8-byte FB at r1 + 0 (x0), i at r1 + 40: a[i].m := v with m at +4 (the
  // ADDI that a call of a[i] or an assignment to its member makes), then load `offset` again.
  const auto reloads = [](uint16_t offset) {
    const Instr ld16 = Instr::abc(Op::LD_U16, 2, 1, offset);
    Instr again = ld16;
    again.a = 7;
    return optimised({ld16, Instr::abc(Op::LD_I16, 3, 1, 40), Instr::abc(Op::INDEX, 4, 3, 0),
                      Instr::abc(Op::ADD, 5, 1, 4), Instr::abc(Op::ADDI, 6, 5, 4), Instr::abc(Op::ST_16, 2, 6, 0), again,
                      Instr::abc(Op::ST_16, 7, 1, 44), kRet},
                     {{0, 4, 8}})
        .code.size();
  };
  EXPECT_EQ(reloads(40), 8u);  // i, past the array: served from r2
  EXPECT_EQ(reloads(2), 8u);   // before the first element's member
  EXPECT_EQ(reloads(30), 8u);  // just past the last element's member
  EXPECT_EQ(reloads(28), 9u);  // the last element's member: read again
  EXPECT_EQ(reloads(12), 9u);  // the second element's member
}

TEST(LoadForwarding, WritingTheHoldingRegisterBeforeTheLastReadKeepsTheLoad) {
  const bc::Module m = optimised({ld(2, 0), ld(3, 0), Instr::asbx(Op::LDI, 2, 9), Instr::abc(Op::ADD, 4, 3, 2),
                                  Instr::abc(Op::ST_32, 4, 1, 8), kRet});
  EXPECT_EQ(m.code.size(), 6u);
}

TEST(LoadForwarding, ALoadWhoseRegisterIsReadInAnotherBlockStays) {
  // 0: r2 := x   1: r3 := x   2: JZ r2 -> 4   3: STK   4: ST r3 (r3 read after the block)   5: RET
  const bc::Module m = optimised({ld(2, 0), ld(3, 0), Instr::asbx(Op::JZ, 2, 1), Instr::abc(Op::STK_32, 1, 1, 8),
                                  Instr::abc(Op::ST_32, 3, 1, 4), kRet});
  EXPECT_EQ(m.code.size(), 6u);
}

TEST(LoadForwarding, AJoinKnowsOnlyWhatEveryPathKnows) {
  // 0: r2 := x   1: JZ r3 -> 3   2: <store>   3: r4 := x   4: ST r4   5: RET
  const auto after = [](Instr arm) {
    return optimised({ld(2, 0), Instr::asbx(Op::JZ, 3, 1), arm, ld(4, 0), Instr::abc(Op::ST_32, 4, 1, 8), kRet})
        .code.size();
  };
  EXPECT_EQ(after(Instr::abc(Op::STK_32, 1, 1, 0)), 6u);  // one arm writes x
  EXPECT_EQ(after(Instr::abc(Op::STK_32, 1, 1, 4)), 5u);  // neither does
}

TEST(LoadForwarding, ACallKeepsOnlyTheCalleesFpAndThisAlive) {
  // 0: r6 := x   1: r7 := x   2: ST r7   3: JMP 4 (ends the block)   4: CALL with its window at r2
  // 5: RET. The call reads r2 and r3 (the callee's fp and this), not r7: the load goes.
  const bc::Module m = optimised({ld(6, 0), ld(7, 0), Instr::abc(Op::ST_32, 7, 1, 8), Instr::asbx(Op::JMP, 0, 0),
                                  Instr::abx(Op::CALL, 2, 0), kRet});
  ASSERT_EQ(m.code.size(), 5u);
  EXPECT_EQ(m.code[1].op, Op::ST_32);
  EXPECT_EQ(m.code[1].a, 6);
}

TEST(LoadForwarding, AStoredRegisterServesTheLoadThatReadsItBackExactly) {
  // r2 := the WORD at 0, stored at 4, then the location at 4 loaded again as `again`.
  const auto word = [](Op again) {
    return optimised({Instr::abc(Op::LD_U16, 2, 1, 0), Instr::abc(Op::ST_16, 2, 1, 4), Instr::abc(again, 3, 1, 4),
                      Instr::abc(Op::ST_32, 3, 1, 8), kRet})
        .code.size();
  };
  EXPECT_EQ(word(Op::LD_U16), 4u);  // zero-extended 16 bits, as stored: served from r2
  EXPECT_EQ(word(Op::LD_I16), 5u);  // 65535 stored reads back as INT -1: memory again
  // r4 := r2 op r3 (r2, r3 loaded), stored with `store`, loaded again with `again`.
  const auto result = [](Op op, Op store, Op again) {
    return optimised({Instr::abc(Op::LD_F32, 2, 1, 0), Instr::abc(Op::LD_F32, 3, 1, 4), Instr::abc(op, 4, 2, 3),
                      Instr::abc(store, 4, 1, 8), Instr::abc(again, 5, 1, 8), Instr::abc(Op::ST_64, 5, 1, 16), kRet})
        .code.size();
  };
  EXPECT_EQ(result(Op::MUL_F32, Op::ST_F32, Op::LD_F32), 6u);  // a REAL result is exactly a float
  EXPECT_EQ(result(Op::MUL_F, Op::ST_F32, Op::LD_F32), 7u);    // an LREAL product is rounded by the store
  EXPECT_EQ(result(Op::ADD, Op::ST_32, Op::LD_I32), 7u);       // a sum may have wrapped past 32 bits
  EXPECT_EQ(result(Op::ADD, Op::ST_64, Op::LD_64), 6u);        // all 64 bits stored
  EXPECT_EQ(result(Op::LT_F, Op::ST_8, Op::LD_U8), 6u);        // a comparison is 0 or 1
}

TEST(LoadForwarding, AStoreOfARegisterWhoseWriterWentServesNothing) {
  // 0: r2 := 7   1: r3 := 7 (served from r2: its store reads r2)   2: ST_64 r3 at 0
  // 3: r3 := the LINT at 0   4: ST_64 r3 at 8. Taking store 2 to mean that r3 holds the LINT
  // at 0 removed load 3 as well, and store 4 read r3, which is no longer written
  // (golden statements/stale_store_constant.st). Both stores must read r2.
  const bc::Module m = optimised({Instr::asbx(Op::LDI, 2, 7), Instr::asbx(Op::LDI, 3, 7), Instr::abc(Op::ST_64, 3, 1, 0),
                                  Instr::abc(Op::LD_64, 3, 1, 0), Instr::abc(Op::ST_64, 3, 1, 8), kRet});
  ASSERT_EQ(m.code.size(), 4u);
  EXPECT_EQ(m.code[1].op, Op::ST_64);
  EXPECT_EQ(m.code[1].a, 2);
  EXPECT_EQ(m.code[2].op, Op::ST_64);
  EXPECT_EQ(m.code[2].a, 2);
}

// The listing of MAIN in the compiled `text`.
std::string listingOfMain(const std::string& text) {
  SourceManager sources;
  Diagnostics diags;
  auto m = compileProgram({{"main.st", text}}, sources, diags);
  if (!m) return "compile error: " + diags.render(sources);
  for (uint32_t p = 0; p < m->pous.size(); ++p)
    if (m->pous[p].name == "MAIN") return bc::disassemble(*m, p);
  return "no MAIN";
}

// The listing of MAIN of a program whose body is `body` over `vars` (DINT x, y, u by default).
std::string mainListing(const std::string& body, const std::string& vars = "x, y, u : DINT;") {
  return listingOfMain("PROGRAM MAIN\nVAR " + vars + " END_VAR\n" + body + "\nEND_PROGRAM\n");
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(LoadForwarding, AForLoopReadsItsControlVariableFromARegister) {
  const std::string l = mainListing("FOR x := 1 TO 10 DO y := y + x; u := u + x * 2; END_FOR");
  // x (offset 0) is loaded before the first test and after each step, never in the body.
  EXPECT_EQ(count(l, "LD_I32   r4, r1, 0\n"), 2u) << l;
  EXPECT_EQ(count(l, ", r1, 0\n"), 3u) << l;  // and stored by the step
  // The test follows the step: one backward compare-and-branch, no JMP.
  EXPECT_EQ(count(l, "  JLE_I "), 1u) << l;
  EXPECT_EQ(count(l, "  JMP "), 0u) << l;
}

TEST(LoadForwarding, AWrappedResultKeepsItsRegisterForTheNextStatement) {
  // j - 1 is sign-extended into a register of its own for the index, so the register holding
  // j - 1 still holds it when the next statement computes it again for the store.
  const std::string l = mainListing("k := a[j - 1];\nj := j - 1;", "a : ARRAY[0..9] OF INT; j, k : INT;");
  EXPECT_EQ(count(l, "  ADDI "), 1u) << l;
  EXPECT_EQ(count(l, "  SEXT "), 1u) << l;
  EXPECT_EQ(count(l, "  LD_I16 "), 2u) << l;  // j and a[j - 1]
}

TEST(LoadForwarding, RenamedReadersServeTheNextBlocksOnTheNextPass) {
  // Block 0..3: r2 := x; r3 := x (served from r2); r4 := INDEX(r3) (then INDEX(r2)).
  // Block 4..: r5 := x (served from r2); r6 := INDEX(r5): its entry facts, from the code as it
  // was, know INDEX(r3) only; the second pass over the renamed code serves it from r4.
  const bc::Module m = optimised({ld(2, 0), ld(3, 0), Instr::abc(Op::INDEX, 4, 3, 0), Instr::asbx(Op::JZ, 2, 0),
                                  ld(5, 0), Instr::abc(Op::INDEX, 6, 5, 0), Instr::abc(Op::ST_32, 6, 1, 8), kRet},
                                 {{0, 4, 2}});
  ASSERT_EQ(m.code.size(), 5u);
  EXPECT_EQ(m.code[3].op, Op::ST_32);
  EXPECT_EQ(m.code[3].a, 4);
}

// A call keeps what the caller loaded where the callee cannot write (bc::thisWriteReach): i is
// loaded once around a call of an FB that writes only its own instance, but fb.y, which it
// writes, is loaded again; a callee that writes a global, or one compiled after its caller
// (whose code is not known yet), makes i be loaded again. Results: statements/call_reloads.st.
TEST(LoadForwarding, ACallKeepsTheLoadsItsCalleeCannotWrite) {
  const std::string fbAcc = "FUNCTION_BLOCK FB_Acc\nVAR_INPUT x : DINT; END_VAR\nVAR_OUTPUT y : DINT; END_VAR\n"
                            "y := y + x;\nEND_FUNCTION_BLOCK\n";
  const std::string fbGlobal = "VAR_GLOBAL g : DINT; END_VAR\nFUNCTION_BLOCK FB_Acc\nVAR_INPUT x : DINT; END_VAR\n"
                               "VAR_OUTPUT y : DINT; END_VAR\ng := x;\nEND_FUNCTION_BLOCK\n";
  const std::string main = "PROGRAM MAIN\nVAR fb : FB_Acc; i, s, t : DINT; END_VAR\n"
                           "s := i + fb.y;\nfb(x := 1);\nt := i + fb.y;\nEND_PROGRAM\n";
  const std::string kept = listingOfMain(fbAcc + main);
  EXPECT_EQ(count(kept, "  LD_I32 "), 3u) << kept;  // i once, fb.y before and after the call
  const std::string global = listingOfMain(fbGlobal + main);
  EXPECT_EQ(count(global, "  LD_I32 "), 4u) << global;
  const std::string later = listingOfMain(main + fbAcc);
  EXPECT_EQ(count(later, "  LD_I32 "), 4u) << later;
}

// The arguments a call stores into its callee's new frame (on the stack above the caller's
// frame) do not hide the caller's variables: i is loaded once for i + Twice(i) + i.
TEST(LoadForwarding, ArgumentsStoredIntoACalleesFrameKeepTheCallersLoads) {
  const std::string l = listingOfMain(
      "FUNCTION Twice : DINT\nVAR_INPUT x : DINT; END_VAR\nTwice := x * 2;\nEND_FUNCTION\n"
      "PROGRAM MAIN\nVAR i, s : DINT; END_VAR\ns := i + Twice(i) + i;\nEND_PROGRAM\n");
  EXPECT_EQ(count(l, "  LD_I32 "), 2u) << l;  // i, and Twice's result from its frame
}

}  // namespace
}  // namespace virtcom::st
