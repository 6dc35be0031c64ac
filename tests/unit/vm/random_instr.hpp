#pragma once
// Random bytecode for robustness and differential tests (vm/, aot/).
#include <random>

#include "bytecode/instruction.hpp"
#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"

namespace virtcom::test {

using bc::Op;
using bc::WideOperand;

// A random instruction for a POU with `numRegs` registers whose code is [start, start + size),
// placed at `pc`, in a module with `pous` POUs, 3 constants and 3 index descriptors. Operands
// are mostly valid; about one in a hundred is not, for the verifier to catch.
inline bc::Instr randomInstr(std::mt19937& rng, uint16_t numRegs, uint32_t pc, uint32_t start, uint32_t size,
                             uint32_t pous = 3) {
  auto pick = [&rng](uint32_t lo, uint32_t hi) { return std::uniform_int_distribution<uint32_t>(lo, hi)(rng); };
  const auto op = static_cast<Op>(pick(0, static_cast<uint32_t>(Op::Count_) - 1));
  const auto rare = [&] { return pick(0, 99) == 0; };  // occasionally an invalid operand
  const auto reg = [&] { return static_cast<uint16_t>(pick(0, numRegs - 1) + (rare() ? 1 : 0)); };
  // A target in [start - 1, start + size) relative to the next instruction (one before the POU
  // is invalid).
  const auto jumpOffset = [&] { return static_cast<int32_t>(pick(start, start + size)) - 1 - static_cast<int32_t>(pc) - 1; };
  if (bc::opFormat(op) == bc::Format::ABC) {
    const auto operand = [&](bc::Operand role) {
      uint16_t v = pick(0, 3) == 0 ? static_cast<uint16_t>(pick(0, 0xffff)) : static_cast<uint16_t>(pick(0, 70));
      switch (role) {
        case bc::Operand::Reg: v = reg(); break;
        case bc::Operand::BitIndex: v = static_cast<uint16_t>(pick(0, 7) + (rare() ? 8 : 0)); break;
        case bc::Operand::BitCount: v = static_cast<uint16_t>(pick(1, 64) + (rare() ? 64 : 0)); break;
        case bc::Operand::Divisor: v = static_cast<uint16_t>(rare() ? 0 : pick(1, 0xffff)); break;
        case bc::Operand::Index: v = static_cast<uint16_t>(pick(0, 2) + (rare() ? 1 : 0)); break;
        case bc::Operand::Branch: v = static_cast<uint16_t>(jumpOffset()); break;
        default: break;
      }
      return v;
    };
    const bc::OperandRoles roles = bc::operandRoles(op);
    const uint16_t a = reg();
    const uint16_t b = roles.b == bc::Operand::Branch ? operand(roles.b) : reg();
    return bc::Instr::abc(op, a, b, operand(roles.c));
  }
  uint32_t bx = 0;
  switch (bc::operandRoles(op).bx) {
    case WideOperand::Abs: bx = rare() ? pick(0, 270) : pick(16, 248); break;
    case WideOperand::Pou: bx = pick(0, pous - 1) + (rare() ? 1 : 0); break;
    case WideOperand::Const: bx = pick(0, 2) + (rare() ? 1 : 0); break;
    case WideOperand::Native: bx = pick(0, static_cast<uint32_t>(bc::Native::Count_) - 1) + (rare() ? 1 : 0); break;
    case WideOperand::NativeFb: bx = pick(0, static_cast<uint32_t>(bc::NativeFb::Count_) - 1) + (rare() ? 1 : 0); break;
    case WideOperand::Jump: return bc::Instr::asbx(op, reg(), jumpOffset());
    case WideOperand::Fault: bx = pick(1, 8) + (rare() ? 1 : 0); break;
    default: bx = pick(0, 3) == 0 ? pick(0, 0xffffffffu) : pick(0, 300); break;
  }
  return bc::Instr::abx(op, reg(), bx);
}

// A module without POUs for random code: small stacks, the 3 constants and 3 index descriptors
// randomInstr() refers to, and static memory above the null guard filled with random bytes.
inline ModuleBuilder randomModuleTables(std::mt19937& rng) {
  ModuleBuilder b(256);
  b.m.stackSize = 512;
  b.m.maxCallDepth = 8;
  b.m.registerStackSize = 64;
  for (int k = 0; k < 3; ++k) b.constant(std::uniform_int_distribution<uint64_t>()(rng) % 600);
  for (int k = 0; k < 3; ++k)
    b.m.indexes.push_back({static_cast<int64_t>(rng() % 600) - 300, 1 + rng() % 300, rng() % 9});
  for (size_t i = 16; i < b.m.initialImage.size(); ++i) b.m.initialImage[i] = static_cast<uint8_t>(rng() % 4 ? rng() : 0);
  return b;
}

}  // namespace virtcom::test
