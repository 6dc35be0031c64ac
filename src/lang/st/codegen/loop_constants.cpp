// Loop-invariant constants (loop_constants.hpp).
#include "lang/st/codegen/loop_constants.hpp"

#include <algorithm>

#include "lang/st/codegen/liveness.hpp"

namespace virtcom::st {

namespace {

using bc::Instr;
using bc::Op;

struct Loop {
  uint32_t head, tail;  // indices from codeStart; tail is the last backward branch to head
};

bool fallsThrough(Op op) { return op != Op::JMP && op != Op::RET && op != Op::TRAP; }

// The loops entered only by falling into their head, in order of their heads.
std::vector<Loop> loops(const std::vector<Instr>& code, uint32_t codeStart, const std::vector<int64_t>& target) {
  const auto n = static_cast<uint32_t>(target.size());
  std::vector<int64_t> tailOf(n, -1);
  for (uint32_t k = 0; k < n; ++k)
    if (target[k] >= 0 && target[k] - codeStart <= k) tailOf[target[k] - codeStart] = k;
  std::vector<Loop> out;
  for (uint32_t head = 1; head < n; ++head) {
    if (tailOf[head] < 0 || !fallsThrough(code[codeStart + head - 1].op)) continue;
    const Loop loop{head, static_cast<uint32_t>(tailOf[head])};
    const auto inside = [&](int64_t k) { return k >= loop.head && k <= loop.tail; };
    bool enteredElsewhere = false;
    for (uint32_t k = 0; k < n && !enteredElsewhere; ++k)
      enteredElsewhere = target[k] >= 0 && !inside(k) && inside(target[k] - codeStart);
    if (!enteredElsewhere) out.push_back(loop);
  }
  return out;
}

bool loadsConstant(const Instr& ins) { return ins.op == Op::LDI || ins.op == Op::LDK; }
bool same(const Instr& x, const Instr& y) { return x.op == y.op && x.a == y.a && x.bx() == y.bx(); }

// Whether the loop's instructions write `reg` other than by `load` itself.
bool writtenBesides(const std::vector<Instr>& code, uint32_t codeStart, const Loop& loop, uint16_t reg, const Instr& load) {
  for (uint32_t j = loop.head; j <= loop.tail; ++j)
    if (writesRegister(code[codeStart + j], reg) && !same(code[codeStart + j], load)) return true;
  return false;
}

// Gives the constant load at k the register `fresh` when every instruction that reads its value
// is after it in its basic block, up to the next write of its register, and the register is dead
// where that stretch ends; false, with nothing changed, otherwise (or if a call's window reads it).
bool giveOwnRegister(std::vector<Instr>& code, uint32_t codeStart, uint32_t k, const std::vector<int64_t>& target,
                     const std::vector<bool>& leader, const Liveness& live, uint16_t numRegs, uint16_t fresh) {
  const auto n = static_cast<uint32_t>(target.size());
  const uint16_t reg = code[codeStart + k].a;
  const auto deadBefore = [&](int64_t j) { return !live.liveBefore(static_cast<uint32_t>(codeStart + j), reg); };
  std::vector<uint16_t*> readers;
  for (uint32_t j = k + 1; j < n; ++j) {
    Instr& ins = code[codeStart + j];
    const RegisterReads reads = registerReads(ins, numRegs);
    if (reg >= reads.windowFrom && reg < reads.windowTo) return false;
    for (int r = 0; r < reads.count; ++r)
      if (*reads.regs[r] == reg) readers.push_back(reads.regs[r]);
    bool ends = writesRegister(ins, reg);
    if (!ends && (bc::isBranch(ins.op) || !fallsThrough(ins.op) || (j + 1 < n && leader[j + 1]))) {
      if (target[j] >= 0 && !deadBefore(target[j] - codeStart)) return false;
      if (fallsThrough(ins.op) && j + 1 < n && !deadBefore(j + 1)) return false;
      ends = true;
    }
    if (!ends) continue;
    code[codeStart + k].a = fresh;
    for (uint16_t* r : readers) *r = fresh;
    return true;
  }
  return false;
}

}  // namespace

std::optional<LoopConstants> takeLoopConstants(std::vector<Instr>& code, uint32_t codeStart, uint32_t end,
                                               const std::vector<int64_t>& target, uint16_t& numRegs, uint16_t maxRegs) {
  const std::vector<Loop> found = loops(code, codeStart, target);
  if (found.empty()) return std::nullopt;
  const Liveness live(code, codeStart, end, numRegs);
  std::vector<bool> leader(target.size(), false);
  for (int64_t t : target)
    if (t >= 0) leader[static_cast<size_t>(t - codeStart)] = true;
  for (const Loop& loop : found) {
    LoopConstants plan{loop.head, {}, {}};
    for (uint32_t k = loop.head; k <= loop.tail; ++k) {
      Instr& load = code[codeStart + k];
      if (!loadsConstant(load) || load.a < 2) continue;
      const auto moved = std::ranges::find_if(plan.moved, [&](uint32_t m) { return same(code[codeStart + m], load); });
      if (moved != plan.moved.end()) continue;  // a repeat, already dropped
      if (live.liveBefore(codeStart + loop.head, load.a) || writtenBesides(code, codeStart, loop, load.a, load)) {
        // Its register holds other values in the loop: a register of its own, if no call in
        // the loop may overwrite that one.
        const uint16_t fresh = numRegs;
        if (fresh >= maxRegs || writtenBesides(code, codeStart, loop, fresh, Instr::asbx(Op::LDI, fresh, 0)) ||
            !giveOwnRegister(code, codeStart, k, target, leader, live, numRegs, fresh))
          continue;
        ++numRegs;
        plan.moved.push_back(k);
        continue;
      }
      plan.moved.push_back(k);
      for (uint32_t j = k + 1; j <= loop.tail; ++j)
        if (same(code[codeStart + j], load)) plan.dropped.push_back(j);
    }
    if (!plan.moved.empty()) return plan;
  }
  return std::nullopt;
}

}  // namespace virtcom::st
