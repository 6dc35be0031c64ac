#include "lang/st/codegen/liveness.hpp"

#include <algorithm>

#include "bytecode/verifier.hpp"

namespace virtcom::st {

using bc::Op;

std::optional<RegisterWrite> registerWrite(const bc::Instr& ins) {
  // A callee's window starts at A; a native writes its result to A only (vm/natives.hpp).
  if (ins.op == Op::CALL) return RegisterWrite{ins.a, true};
  if (ins.op == Op::CALLN) return RegisterWrite{ins.a, false};
  if (bc::writesOnlyA(ins.op)) return RegisterWrite{ins.a, false};
  return std::nullopt;
}

RegisterReads registerReads(bc::Instr& ins, uint16_t numRegs) {
  RegisterReads r;
  const bc::OperandRoles roles = bc::operandRoles(ins.op);
  if (ins.op == Op::CALL) {  // the callee's r0 and r1 (liveness.hpp)
    r.windowFrom = ins.a;
    r.windowTo = std::min<uint32_t>(ins.a + 2u, numRegs);
    return r;
  }
  if (ins.op == Op::CALLN) {
    r.windowFrom = ins.a;
    r.windowTo = ins.a + bc::nativeArity(static_cast<bc::Native>(ins.bx()));
    return r;
  }
  if (roles.a == bc::Operand::Reg && !bc::writesOnlyA(ins.op)) r.regs[r.count++] = &ins.a;
  if (bc::opFormat(ins.op) == bc::Format::ABC) {
    if (roles.b == bc::Operand::Reg) r.regs[r.count++] = &ins.b;
    if (roles.c == bc::Operand::Reg) r.regs[r.count++] = &ins.c;
  }
  return r;
}


bool writesRegister(const bc::Instr& ins, uint16_t reg) {
  const std::optional<RegisterWrite> w = registerWrite(ins);
  return w && (reg == w->reg || (w->andAbove && reg > w->reg));
}

Liveness::Liveness(const std::vector<bc::Instr>& code, uint32_t begin, uint32_t end, uint16_t numRegs)
    : code_(code), begin_(begin), n_(end - begin), regs_(numRegs), words_((numRegs + 63u) / 64u),
      live_(size_t{n_} * words_, 0) {
  for (bool changed = true; changed;) {
    changed = false;
    for (uint32_t k = n_; k-- > 0;) changed |= update(k);
  }
}

bool Liveness::update(uint32_t k) {
  const bc::Instr& ins = code_[begin_ + k];
  Set s(words_, 0);
  if (ins.op == Op::RET) {
    add(s, 0);
    add(s, 1);
  } else if (ins.op != Op::TRAP) {
    if (ins.op != Op::JMP && k + 1 < n_) unionWith(s, k + 1);
    if (bc::isBranch(ins.op)) unionWith(s, static_cast<uint32_t>(bc::branchTarget(begin_ + k, ins) - begin_));
  }
  const bc::OperandRoles roles = bc::operandRoles(ins.op);
  if (bc::writesOnlyA(ins.op)) {
    if (ins.a < regs_) s[ins.a / 64u] &= ~(uint64_t{1} << (ins.a % 64u));
  }
  else if (roles.a == bc::Operand::Reg) add(s, ins.a);
  if (ins.op == Op::CALL) {
    add(s, ins.a);
    add(s, ins.a + 1u);
  }
  if (ins.op == Op::CALLN)
    for (uint32_t r = ins.a; r < ins.a + bc::nativeArity(static_cast<bc::Native>(ins.bx())); ++r) add(s, r);
  if (bc::opFormat(ins.op) == bc::Format::ABC) {
    if (roles.b == bc::Operand::Reg) add(s, ins.b);
    if (roles.c == bc::Operand::Reg) add(s, ins.c);
  }
  uint64_t* slot = &live_[size_t{k} * words_];
  if (std::equal(s.begin(), s.end(), slot)) return false;
  std::copy(s.begin(), s.end(), slot);
  return true;
}

}  // namespace virtcom::st
