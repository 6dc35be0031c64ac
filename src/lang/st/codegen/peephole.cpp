// The peephole pass (peephole.hpp). Code generation emits a condition as a comparison into a
// register followed by JZ/JNZ on that register; the interpreter pays a dispatch for each, so the
// pair becomes one fused compare-and-branch wherever the register is dead afterwards.
#include "lang/st/codegen/peephole.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <vector>

#include "bytecode/verifier.hpp"

namespace virtcom::st {

namespace {

using bc::Instr;
using bc::Op;

// Registers live before each instruction of one POU: backward dataflow to a fixed point. At CALL
// every register from A up is live (the callee's window). After RET only r0 and r1: the code
// generator passes parameters and results through memory, so a caller reads nothing of the
// callee's window after the call but the frame pointer it set up itself.
class Liveness {
 public:
  Liveness(const std::vector<Instr>& code, uint32_t begin, uint32_t end, uint16_t numRegs)
      : code_(code), begin_(begin), n_(end - begin), regs_(numRegs), words_((numRegs + 63u) / 64u),
        live_(size_t{n_} * words_, 0) {
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t k = n_; k-- > 0;) changed |= update(k);
    }
  }

  bool liveBefore(uint32_t pc, uint16_t reg) const {
    const uint32_t k = pc - begin_;
    return reg < regs_ && (live_[size_t{k} * words_ + reg / 64u] >> (reg % 64u) & 1u);
  }

 private:
  using Set = std::vector<uint64_t>;

  void add(Set& s, uint32_t reg) const {
    if (reg < regs_) s[reg / 64u] |= uint64_t{1} << (reg % 64u);
  }
  void unionWith(Set& s, uint32_t k) const {
    for (uint32_t w = 0; w < words_; ++w) s[w] |= live_[size_t{k} * words_ + w];
  }

  // Recomputes live-before of instruction k; true if it changed.
  bool update(uint32_t k) {
    const Instr& ins = code_[begin_ + k];
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
    if (ins.op == Op::CALL)
      for (uint32_t r = ins.a; r < regs_; ++r) add(s, r);
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

  const std::vector<Instr>& code_;
  uint32_t begin_, n_, regs_, words_;
  std::vector<uint64_t> live_;
};

// The fused branch that jumps where `jump` (JZ or JNZ on cmp's result) would, with its offset
// still to be set; nullopt if `cmp` is no comparison that has one.
std::optional<Instr> fuse(const Instr& cmp, Op jump) {
  const bool ifTrue = jump == Op::JNZ;
  const auto reg = [&](Op op, bool swap) {
    return Instr::abc(op, swap ? cmp.c : cmp.b, swap ? cmp.b : cmp.c, 0);
  };
  const auto konst = [&](Op op) { return Instr::abc(op, cmp.b, 0, cmp.c); };
  switch (cmp.op) {
    // Jump if false: a == b fails as a != b; a < b fails as b <= a (integers only: no NaN).
    case Op::EQ: return reg(ifTrue ? Op::JEQ : Op::JNE, false);
    case Op::NE: return reg(ifTrue ? Op::JNE : Op::JEQ, false);
    case Op::LT_I: return ifTrue ? reg(Op::JLT_I, false) : reg(Op::JLE_I, true);
    case Op::LE_I: return ifTrue ? reg(Op::JLE_I, false) : reg(Op::JLT_I, true);
    case Op::LT_U: return ifTrue ? reg(Op::JLT_U, false) : reg(Op::JLE_U, true);
    case Op::LE_U: return ifTrue ? reg(Op::JLE_U, false) : reg(Op::JLT_U, true);
    case Op::EQK: return konst(ifTrue ? Op::JEQK : Op::JNEK);
    case Op::NEK: return konst(ifTrue ? Op::JNEK : Op::JEQK);
    case Op::LTK: return konst(ifTrue ? Op::JLTK : Op::JGEK);
    case Op::LEK: return konst(ifTrue ? Op::JLEK : Op::JGTK);
    case Op::GTK: return konst(ifTrue ? Op::JGTK : Op::JLEK);
    case Op::GEK: return konst(ifTrue ? Op::JGEK : Op::JLTK);
    // NOT x, then a test of the result: the opposite test of x.
    case Op::LNOT: return Instr::asbx(ifTrue ? Op::JZ : Op::JNZ, cmp.b, 0);
    default: return std::nullopt;
  }
}

}  // namespace

void optimizePou(bc::Module& m, uint32_t codeStart, size_t firstLine, uint16_t numRegs) {
  std::vector<Instr>& code = m.code;
  const uint32_t end = static_cast<uint32_t>(code.size());
  if (end <= codeStart + 1) return;
  const uint32_t n = end - codeStart;
  // Absolute branch targets (-1: no branch), and which instructions are targets.
  std::vector<int64_t> target(n, -1);
  std::vector<bool> isTarget(n, false);
  for (uint32_t k = 0; k < n; ++k) {
    if (!bc::isBranch(code[codeStart + k].op)) continue;
    target[k] = bc::branchTarget(codeStart + k, code[codeStart + k]);
    if (target[k] < codeStart || target[k] >= end) return;  // not verifiable code: leave it alone
    isTarget[static_cast<size_t>(target[k] - codeStart)] = true;
  }
  const Liveness live(code, codeStart, end, numRegs);
  std::vector<bool> removed(n, false);
  for (uint32_t k = 0; k + 1 < n; ++k) {
    const Instr& cmp = code[codeStart + k];
    const Instr& jump = code[codeStart + k + 1];
    if ((jump.op != Op::JZ && jump.op != Op::JNZ) || jump.a != cmp.a || !bc::writesOnlyA(cmp.op)) continue;
    if (isTarget[k + 1] || removed[k]) continue;
    const uint32_t to = static_cast<uint32_t>(target[k + 1]);
    if (live.liveBefore(to, cmp.a) || live.liveBefore(codeStart + k + 2, cmp.a)) continue;
    const std::optional<Instr> fused = fuse(cmp, jump.op);
    // Removing instructions only shortens distances, so the offset from here bounds the final one.
    if (!fused || std::abs(int64_t{to} - (codeStart + k + 1)) > bc::maxBranchOffset(fused->op)) continue;
    code[codeStart + k] = *fused;
    target[k] = to;
    target[k + 1] = -1;
    removed[k + 1] = true;
  }
  // Compact; a removed instruction's new index is that of the next one kept (for line entries).
  std::vector<uint32_t> newIndex(n + 1);
  uint32_t kept = 0;
  for (uint32_t k = 0; k < n; ++k) {
    newIndex[k] = codeStart + kept;
    if (!removed[k]) ++kept;
  }
  newIndex[n] = codeStart + kept;
  for (uint32_t k = 0; k < n; ++k) {
    if (removed[k]) continue;
    Instr ins = code[codeStart + k];
    if (target[k] >= 0) {
      const int64_t to = newIndex[static_cast<size_t>(target[k] - codeStart)];
      ins = bc::withBranchOffset(ins, static_cast<int32_t>(to - newIndex[k] - 1));
    }
    code[newIndex[k]] = ins;
  }
  code.resize(codeStart + kept);
  for (size_t i = firstLine; i < m.lines.size(); ++i)
    if (m.lines[i].pc >= codeStart && m.lines[i].pc < end) m.lines[i].pc = newIndex[m.lines[i].pc - codeStart];
}

}  // namespace virtcom::st
