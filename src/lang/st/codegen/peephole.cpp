// The peephole pass (peephole.hpp). Code generation emits a condition as a comparison into a
// register followed by JZ/JNZ on that register; the interpreter pays a dispatch for each, so the
// pair becomes one fused compare-and-branch wherever the register is dead afterwards.
#include "lang/st/codegen/peephole.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <vector>

#include "bytecode/verifier.hpp"
#include "lang/st/codegen/liveness.hpp"
#include "lang/st/codegen/load_forwarding.hpp"
#include "lang/st/codegen/loop_constants.hpp"

namespace virtcom::st {

namespace {

using bc::Instr;
using bc::Op;

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

// Absolute branch targets of code[codeStart, end) by index from codeStart (-1: no branch);
// nullopt if a branch leaves the range (not verifiable code: the passes leave it alone).
std::optional<std::vector<int64_t>> branchTargets(const std::vector<Instr>& code, uint32_t codeStart, uint32_t end) {
  std::vector<int64_t> target(end - codeStart, -1);
  for (uint32_t k = 0; k < target.size(); ++k) {
    if (!bc::isBranch(code[codeStart + k].op)) continue;
    target[k] = bc::branchTarget(codeStart + k, code[codeStart + k]);
    if (target[k] < codeStart || target[k] >= end) return std::nullopt;
  }
  return target;
}

// Rewrites m.code[codeStart, codeStart + n) as the instructions `order` lists (by index from
// codeStart, each at most once; those not listed are dropped), sets the branches' offsets from
// `target` and renumbers the line entries from firstLine on. A branch or line entry that pointed
// at an instruction that does not stay in place (dropped, or moved by `order`) points at the next
// one that does. False, with nothing changed, if a branch offset no longer fits.
bool relayout(bc::Module& m, uint32_t codeStart, size_t firstLine, const std::vector<uint32_t>& order, const std::vector<bool>& inPlace,
              const std::vector<int64_t>& target) {
  std::vector<Instr>& code = m.code;
  const uint32_t n = static_cast<uint32_t>(inPlace.size());
  std::vector<uint32_t> newIndex(n + 1, codeStart + static_cast<uint32_t>(order.size()));
  for (uint32_t i = 0; i < order.size(); ++i) newIndex[order[i]] = codeStart + i;
  std::vector<uint32_t> landing(n + 1, newIndex[n]);  // where a branch to k, or k's line entry, now lands
  for (uint32_t k = n; k-- > 0;) landing[k] = inPlace[k] ? newIndex[k] : landing[k + 1];
  std::vector<Instr> out(order.size());
  for (uint32_t i = 0; i < order.size(); ++i) {
    const uint32_t k = order[i];
    out[i] = code[codeStart + k];
    if (target[k] < 0) continue;
    const int64_t offset = int64_t{landing[static_cast<size_t>(target[k] - codeStart)]} - (codeStart + i) - 1;
    if (std::abs(offset) > bc::maxBranchOffset(out[i].op)) return false;
    out[i] = bc::withBranchOffset(out[i], static_cast<int32_t>(offset));
  }
  code.resize(codeStart);
  code.insert(code.end(), out.begin(), out.end());
  for (size_t i = firstLine; i < m.lines.size(); ++i)
    if (m.lines[i].pc >= codeStart && m.lines[i].pc < codeStart + n) m.lines[i].pc = landing[m.lines[i].pc - codeStart];
  return true;
}

// Drops the instructions marked `removed` (which only shortens branches).
void compact(bc::Module& m, uint32_t codeStart, size_t firstLine, const std::vector<bool>& removed,
             const std::vector<int64_t>& target) {
  std::vector<uint32_t> order;
  for (uint32_t k = 0; k < removed.size(); ++k)
    if (!removed[k]) order.push_back(k);
  std::vector<bool> inPlace(removed.size());
  for (size_t k = 0; k < removed.size(); ++k) inPlace[k] = !removed[k];
  relayout(m, codeStart, firstLine, order, inPlace, target);
}

// Fuses each comparison with the JZ/JNZ testing it where the register is dead afterwards.
void fuseBranches(bc::Module& m, uint32_t codeStart, size_t firstLine, uint16_t numRegs) {
  std::vector<Instr>& code = m.code;
  const uint32_t end = static_cast<uint32_t>(code.size());
  const uint32_t n = end - codeStart;
  std::optional<std::vector<int64_t>> targets = branchTargets(code, codeStart, end);
  if (!targets) return;
  std::vector<int64_t>& target = *targets;
  std::vector<bool> isTarget(n, false);
  for (int64_t t : target)
    if (t >= 0) isTarget[static_cast<size_t>(t - codeStart)] = true;
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
  compact(m, codeStart, firstLine, removed, target);
}

// Loads the constants of each loop once, before it (loop_constants.hpp): one loop at a time, so an
// inner loop's constant may then leave its outer loop too. At most kLoopConstantRegisters
// registers are added to the POU's window (and never beyond code generation's limit).
constexpr uint16_t kLoopConstantRegisters = 64;
void hoistLoopConstants(bc::Module& m, uint32_t codeStart, size_t firstLine, uint16_t& numRegs) {
  const auto maxRegs = static_cast<uint16_t>(std::min<uint32_t>(numRegs + kLoopConstantRegisters, 0xfff0));
  for (;;) {
    const auto end = static_cast<uint32_t>(m.code.size());
    const std::optional<std::vector<int64_t>> targets = branchTargets(m.code, codeStart, end);
    if (!targets) return;
    const std::optional<LoopConstants> plan = takeLoopConstants(m.code, codeStart, end, *targets, numRegs, maxRegs);
    if (!plan) return;
    std::vector<bool> inPlace(end - codeStart, true);
    for (uint32_t k : plan->moved) inPlace[k] = false;
    for (uint32_t k : plan->dropped) inPlace[k] = false;
    std::vector<uint32_t> order;
    for (uint32_t k = 0; k < inPlace.size(); ++k) {
      if (k == plan->head) order.insert(order.end(), plan->moved.begin(), plan->moved.end());
      if (inPlace[k]) order.push_back(k);
    }
    // Each round takes at least one load out of a loop; a branch that no longer reaches ends them.
    if (!relayout(m, codeStart, firstLine, order, inPlace, *targets)) return;
  }
}

}  // namespace

uint16_t optimizePou(bc::Module& m, uint32_t codeStart, size_t firstLine, uint16_t numRegs) {
  // Forwarding renames the readers of a removed load, after which a later block may repeat a
  // computation on the renamed register (`INDEX r12, r5` where it knew `INDEX r6, r5` only by its
  // old operand): run it again on its own result until it removes nothing.
  for (;;) {
    const uint32_t end = static_cast<uint32_t>(m.code.size());
    if (end <= codeStart + 1) return numRegs;
    const std::optional<std::vector<int64_t>> targets = branchTargets(m.code, codeStart, end);
    if (!targets) return numRegs;
    const std::vector<bool> removed = forwardLoads(m, codeStart, end, numRegs);
    if (std::none_of(removed.begin(), removed.end(), [](bool r) { return r; })) break;
    compact(m, codeStart, firstLine, removed, *targets);
  }
  hoistLoopConstants(m, codeStart, firstLine, numRegs);
  fuseBranches(m, codeStart, firstLine, numRegs);
  return numRegs;
}

}  // namespace virtcom::st
