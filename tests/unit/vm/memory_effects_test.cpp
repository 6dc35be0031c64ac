// What an instruction reads and writes, and what a call of a POU may write
// (bytecode/memory_effects.hpp), on hand-assembled POUs.
#include "bytecode/memory_effects.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "test_module_builder.hpp"

namespace virtcom {
namespace {

using bc::Instr;
using bc::Op;
using test::abc;
using test::abx;
using test::ModuleBuilder;

// bc::thisWriteReach of a function block whose code is `body` then RET, with array shape x0 =
// ARRAY[0..3] of 8-byte elements.
std::optional<uint64_t> reachOf(const std::vector<Instr>& body) {
  ModuleBuilder b;
  b.m.indexes.push_back({0, 4, 8});
  b.beginPou("FB", 8, 16, 0, bc::PouKind::FunctionBlock);
  for (const Instr& ins : body) b.emit(ins);
  b.emit(abc(Op::RET));
  return bc::thisWriteReach(b.m, b.m.pous[0]);
}

TEST(MemoryEffects, RangesCoverTheBytesAnAccessTouches) {
  EXPECT_EQ(bc::loadedRange(abc(Op::LD_I16, 2, 1, 6))->offset, 6u);
  EXPECT_EQ(bc::loadedRange(abc(Op::LD_I16, 2, 1, 6))->width, 2u);
  EXPECT_EQ(bc::loadedRange(abc(Op::LD_BIT, 2, 1, 5))->offset, 0u);  // C is the bit: its byte
  EXPECT_TRUE(bc::loadedRange(abx(Op::LDA_64, 2, 300))->absolute);
  EXPECT_EQ(bc::loadedRange(abx(Op::LDA_64, 2, 300))->width, 8u);
  EXPECT_FALSE(bc::loadedRange(abc(Op::ST_32, 2, 1, 0)));
  EXPECT_EQ(bc::storedRange(abc(Op::STK_32, 7, 3, 12))->base, 3u);
  EXPECT_EQ(bc::storedRange(abc(Op::STK_32, 7, 3, 12))->width, 4u);
  const bc::MemoryRange ton = *bc::storedRange(abx(Op::CALLFB, 4, static_cast<uint32_t>(bc::NativeFb::TON)));
  EXPECT_EQ(ton.base, 4u);
  EXPECT_EQ(ton.width, bc::nativeFbSize(bc::NativeFb::TON));
  EXPECT_FALSE(bc::storedRange(abc(Op::COPY, 2, 3, 4)));
  EXPECT_TRUE(bc::writesBeyondRanges(Op::COPY));
  EXPECT_FALSE(bc::writesBeyondRanges(Op::ST_32));
}

TEST(MemoryEffects, ACalleeThatWritesOnlyItsInstanceReachesItsLastByte) {
  EXPECT_EQ(reachOf({abc(Op::LD_I32, 2, 1, 0), abc(Op::ST_32, 2, 1, 8)}), 12u);
  EXPECT_EQ(reachOf({abc(Op::ST_BIT, 2, 1, 7)}), 1u);
  // its frame (fp) and the ENTER of a callee's frame: the stack, not counted
  EXPECT_EQ(reachOf({abc(Op::STK_64, 0, 0, 8), abx(Op::ENTER, 4, 0)}), 0u);
  // an element of ARRAY[0..3] at this + 0, then a member at +2 of it: 3 * 8 + 2 + 2 bytes
  EXPECT_EQ(reachOf({abc(Op::LD_I16, 2, 1, 40), abc(Op::INDEX, 3, 2, 0), abc(Op::ADD, 4, 1, 3),
                     abc(Op::ADDI, 5, 4, 2), abc(Op::ST_16, 2, 5, 0)}),
            28u);
  EXPECT_EQ(reachOf({abc(Op::ADDI, 5, 1, 16), abx(Op::CALLFB, 5, static_cast<uint32_t>(bc::NativeFb::TON))}),
            16 + bc::nativeFbSize(bc::NativeFb::TON));
}

TEST(MemoryEffects, ACalleeThatMayWriteElsewhereHasNoReach) {
  EXPECT_FALSE(reachOf({abx(Op::STA_32, 2, 64)}));                          // a global
  EXPECT_FALSE(reachOf({abc(Op::LD_64, 2, 1, 0), abc(Op::ST_32, 3, 2, 0)}));  // through a pointer
  EXPECT_FALSE(reachOf({abc(Op::COPY, 2, 3, 4)}));
  EXPECT_FALSE(reachOf({abx(Op::ENTER, 4, 0), abx(Op::CALL, 4, 0)}));  // another POU
  EXPECT_FALSE(reachOf({abx(Op::CALLN, 4, 0)}));
  EXPECT_FALSE(reachOf({abc(Op::MOV, 1, 2)}));  // this itself changes
  ModuleBuilder b;
  b.beginPou("FB", 4, 0, 0, bc::PouKind::FunctionBlock);  // still being compiled: no code yet
  EXPECT_FALSE(bc::thisWriteReach(b.m, b.m.pous[0]));
}

}  // namespace
}  // namespace virtcom
