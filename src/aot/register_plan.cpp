#include "aot/register_plan.hpp"

#include <algorithm>

#include "aot/opcode_snippets.hpp"

namespace virtcom::aot {

namespace {

using bc::Instr;
using bc::Op;

// Adds `from` shifted by `shift` slots (negative: down, dropping what falls below 0) to
// `into`, growing it as needed unless `fixedSize`. True if `into` changed.
bool addShifted(RegisterSet& into, const RegisterSet& from, int64_t shift, bool fixedSize) {
  bool changed = false;
  for (size_t k = 0; k < from.size(); ++k) {
    if (!from[k] || static_cast<int64_t>(k) + shift < 0) continue;
    const auto to = static_cast<size_t>(static_cast<int64_t>(k) + shift);
    if (to >= into.size()) {
      if (fixedSize) continue;
      into.resize(to + 1, false);
    }
    if (into[to]) continue;
    into[to] = true;
    changed = true;
  }
  return changed;
}

void addRange(RegisterSet& s, uint32_t from, uint32_t to) {
  for (uint32_t k = from; k < std::min<uint32_t>(to, static_cast<uint32_t>(s.size())); ++k) s[k] = true;
}

// The slots of `s` at or above `from`.
RegisterSet slotsFrom(const RegisterSet& s, uint32_t from) {
  RegisterSet out(s.size(), false);
  for (size_t k = from; k < s.size(); ++k) out[k] = s[k];
  return out;
}

// Backward liveness over the registers of one POU's window, given the inputs of every POU
// and the slots this POU's callers read after it returns (`visible`).
class PouLiveness {
 public:
  PouLiveness(const bc::Module& m, const bc::PouInfo& pou, const std::vector<RegisterSet>& inputs,
              const RegisterSet& visible)
      : m_(m), pou_(pou), inputs_(inputs), visible_(visible),
        live_(pou.codeSize, RegisterSet(pou.numRegs, false)), afterCall_(pou.codeSize) {}

  void solve() {
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t k = pou_.codeSize; k-- > 0;) {
        RegisterSet in = liveBefore(k);
        if (in != live_[k]) {
          live_[k] = std::move(in);
          changed = true;
        }
      }
    }
  }

  const RegisterSet& liveOnEntry() const { return live_[0]; }
  std::vector<RegisterSet>& liveAfterCall() { return afterCall_; }

 private:
  const Instr& at(uint32_t k) const { return m_.code[pou_.codeStart + k]; }
  uint32_t target(uint32_t k) const { return static_cast<uint32_t>(bc::branchTarget(k, at(k))); }

  // Live after instruction k: the union over its successors; RET hands on the registers its
  // callers read back, TRAP (a fault) nothing.
  RegisterSet liveAfter(uint32_t k) const {
    RegisterSet out(pou_.numRegs, false);
    switch (at(k).op) {
      case Op::RET: addShifted(out, visible_, 0, true); break;
      case Op::TRAP: break;
      case Op::JMP: out = live_[target(k)]; break;
      default:
        out = live_[k + 1];  // the verifier lets no POU fall off its end
        if (bc::isBranch(at(k).op)) addShifted(out, live_[target(k)], 0, true);
        break;
    }
    return out;
  }

  RegisterSet liveBefore(uint32_t k) {
    const Instr& ins = at(k);
    RegisterSet in = liveAfter(k);
    switch (ins.op) {
      case Op::CALL:
        // No kill: a register live after the call is stored before it and reloaded after.
        afterCall_[k] = in;
        in[ins.a] = true;  // the frame pointer test on return reads it
        addShifted(in, inputs_[ins.bx()], ins.a, true);
        break;
      case Op::CALLN:
        addRange(in, ins.a, ins.a + std::max(1u, bc::nativeArity(static_cast<bc::Native>(ins.bx()))));
        break;
      default: {
        const RegisterAccess r = registerAccess(ins.op);
        if (r.writesA) in[ins.a] = false;
        if (r.readsA) in[ins.a] = true;
        if (r.readsB) in[ins.b] = true;
        if (r.readsC) in[ins.c] = true;
      }
    }
    return in;
  }

  const bc::Module& m_;
  const bc::PouInfo& pou_;
  const std::vector<RegisterSet>& inputs_;
  const RegisterSet& visible_;
  std::vector<RegisterSet> live_;  // live before each instruction
  std::vector<RegisterSet> afterCall_;
};

}  // namespace

RegisterPlan planRegisters(const bc::Module& m) {
  const auto count = static_cast<uint32_t>(m.pous.size());
  RegisterPlan plan;
  plan.inputs.assign(count, RegisterSet{});
  plan.pous.resize(count);
  // visible[p]: the slots of p's window its callers read after it returns.
  std::vector<RegisterSet> visible(count);
  for (bool changed = true; changed;) {
    changed = false;
    for (uint32_t p = 0; p < count; ++p) {
      const bc::PouInfo& pou = m.pous[p];
      PouLiveness live(m, pou, plan.inputs, visible[p]);
      live.solve();
      changed |= addShifted(plan.inputs[p], live.liveOnEntry(), 0, false);
      const RegisterSet beyondWindow = slotsFrom(visible[p], pou.numRegs);
      for (uint32_t k = 0; k < pou.codeSize; ++k) {
        const Instr& ins = m.code[pou.codeStart + k];
        if (ins.op != Op::CALL) continue;
        const uint32_t callee = ins.bx();
        // The callee's inputs beyond this window come from this POU's caller; what this POU's
        // callers read beyond its window, its callees may have left there.
        changed |= addShifted(plan.inputs[p], slotsFrom(plan.inputs[callee], pou.numRegs - ins.a), ins.a, false);
        changed |= addShifted(visible[callee], slotsFrom(live.liveAfterCall()[k], ins.a), -int64_t{ins.a}, false);
        changed |= addShifted(visible[callee], beyondWindow, -int64_t{ins.a}, false);
      }
      PouRegisters& out = plan.pous[p];
      out.loadOnEntry = live.liveOnEntry();
      out.writeBack.assign(pou.numRegs, false);
      addShifted(out.writeBack, visible[p], 0, true);
      out.liveAfterCall = std::move(live.liveAfterCall());
    }
  }
  return plan;
}

}  // namespace virtcom::aot
