#include "vm/quicken.hpp"

#include <algorithm>
#include <optional>

#include "bytecode/memory_effects.hpp"
#include "bytecode/verifier.hpp"
#include "vm/natives.hpp"

namespace virtcom::vm {

namespace {

using bc::Instr;
using bc::Op;

// The quickened form of `op`, if it has one.
std::optional<QuickOp> quickForm(Op op) {
  switch (op) {
#define Q(name) \
  case Op::name: return QuickOp::name;
    VIRTCOM_VM_QUICK_OPS(Q)
#undef Q
    default: return std::nullopt;
  }
}

// The specialised form of the instruction at `at` on its own or with the ones after it (up to
// `end`, the end of its POU), for every POU: SEXT/ZEXT of the IEC widths, INDEX_ADD, ENTER0,
// ENTER0_CALL.
std::optional<QuickOp> specialForm(const bc::Module& m, const Instr* at, const Instr* end) {
  const Instr& ins = *at;
  if (ins.op == Op::INDEX && end - at >= 2 && at[1].op == Op::ADD) return QuickOp::INDEX_ADD;
  if (ins.op == Op::ENTER && m.pous[ins.bx()].frameSize == 0) {
    const bool call = end - at >= 3 && at[1].op == Op::MOV && at[2].op == Op::CALL;
    return call ? QuickOp::ENTER0_CALL : QuickOp::ENTER0;
  }
  if (ins.op != Op::SEXT && ins.op != Op::ZEXT) return std::nullopt;
  const bool sext = ins.op == Op::SEXT;
  switch (ins.c) {
    case 8: return sext ? QuickOp::SEXT8 : QuickOp::ZEXT8;
    case 16: return sext ? QuickOp::SEXT16 : QuickOp::ZEXT16;
    case 32: return sext ? QuickOp::SEXT32 : QuickOp::ZEXT32;
    default: return std::nullopt;
  }
}

// The FOR_NEXT form of the quickened code at `at` (QuickOp comment), if the four instructions
// from there are a FOR loop's step, store, reload and test of one register and one location.
std::optional<QuickOp> forNextForm(const Instr* at, const Instr* end) {
  if (end - at < 4) return std::nullopt;
  const Instr& step = at[0];
  const Instr& store = at[1];
  const Instr& load = at[2];
  // The base must not be the stepped register: the fused handler addresses with it as it was.
  if (step.op != Op::ADDI || step.b != step.a || store.a != step.a || load.a != step.a || load.b != store.b ||
      load.c != store.c || store.b == step.a || at[3].op != Op::JLE_I)
    return std::nullopt;
  if (store.op == quickOpcode(QuickOp::ST_16) && load.op == quickOpcode(QuickOp::LD_I16)) return QuickOp::FOR_NEXT_I16;
  if (store.op == quickOpcode(QuickOp::ST_32) && load.op == quickOpcode(QuickOp::LD_I32)) return QuickOp::FOR_NEXT_I32;
  return std::nullopt;
}

}  // namespace

QuickCode quicken(const bc::Module& m, uint64_t memorySize) {
  QuickCode q{m.code, std::vector<PouEntry>(m.pous.size())};
  const uint64_t guard = bc::Module::kNullGuard;
  for (size_t pou = 0; pou < m.pous.size(); ++pou) {
    const bc::PouInfo& p = m.pous[pou];
    PouEntry& e = q.entry[pou];
    e.codeStart = p.codeStart;
    e.numRegs = p.numRegs;
    if (!bc::basesReadOnly(m, p)) continue;
    // Each access with a placed base, and how far past fp or this it may reach; one whose reach
    // memory could never hold stays checked (its fault is then the program's).
    const std::vector<std::optional<bc::Placed>> placed = bc::placedBases(m, p);
    std::vector<bool> quick(p.codeSize, false);
    uint64_t extent[2] = {0, 0};  // fp, this
    for (uint32_t k = 0; k < p.codeSize; ++k) {
      const Instr& ins = m.code[p.codeStart + k];
      const bool fb = ins.op == Op::CALLFB && ins.bx() < kNativeFbSizes.size();
      if (!placed[k] || !(quickForm(ins.op) || fb)) continue;
      std::optional<bc::MemoryRange> range = bc::loadedRange(ins);
      if (!range) range = bc::storedRange(ins);  // a store, or a standard FB's instance
      const uint64_t reach = placed[k]->reach + range->offset + range->width;
      if (reach + guard > memorySize) continue;
      quick[k] = true;
      extent[placed[k]->base] = std::max(extent[placed[k]->base], reach);
    }
    e.lo = guard;
    if (extent[0]) e.fpSpan = memorySize - extent[0] - guard;
    if (extent[1]) e.thisSpan = memorySize - extent[1] - guard;
    for (uint32_t k = 0; k < p.codeSize; ++k) {
      Instr& ins = q.code[p.codeStart + k];
      if (quick[k]) ins.op = quickOpcode(ins.op == Op::CALLFB ? QuickOp::CALLFB : *quickForm(ins.op));
    }
    const Instr* const end = q.code.data() + p.codeStart + p.codeSize;
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc)
      if (const std::optional<QuickOp> fused = forNextForm(&q.code[pc], end)) q.code[pc].op = quickOpcode(*fused);
  }
  for (const bc::PouInfo& p : m.pous) {
    const Instr* const end = q.code.data() + p.codeStart + p.codeSize;
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc)
      if (const std::optional<QuickOp> special = specialForm(m, &q.code[pc], end)) q.code[pc].op = quickOpcode(*special);
  }
  return q;
}

}  // namespace virtcom::vm
