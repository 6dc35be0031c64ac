#include "vm/quicken.hpp"

#include <algorithm>
#include <optional>

#include "bytecode/verifier.hpp"

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

uint32_t accessWidth(Op op) {
  switch (op) {
    case Op::LD_I16: case Op::LD_U16: case Op::ST_16: case Op::STK_16: return 2;
    case Op::LD_I32: case Op::LD_U32: case Op::LD_F32: case Op::ST_32: case Op::ST_F32: case Op::STK_32: return 4;
    case Op::LD_64: case Op::ST_64: case Op::STK_64: return 8;
    default: return 1;
  }
}

// True if no instruction of the POU can change r0 or r1 of its window.
bool basesReadOnly(const bc::Module& m, const bc::PouInfo& p) {
  const auto begin = m.code.begin() + p.codeStart;
  return std::none_of(begin, begin + p.codeSize, [](const Instr& ins) {
    const bool windowBelow2 = ins.op == Op::CALL || ins.op == Op::CALLN;
    return ins.a < 2 && (bc::writesOnlyA(ins.op) || windowBelow2);
  });
}

// The specialised form of an instruction on its own or with the one after it (`next`, null at
// the end of its POU), for every POU: SEXT/ZEXT of the IEC widths, INDEX_ADD, ENTER0.
std::optional<QuickOp> specialForm(const bc::Module& m, const Instr& ins, const Instr* next) {
  if (ins.op == Op::INDEX && next && next->op == Op::ADD) return QuickOp::INDEX_ADD;
  if (ins.op == Op::ENTER && m.pous[ins.bx()].frameSize == 0) return QuickOp::ENTER0;
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
  if (step.op != Op::ADDI || step.b != step.a || store.a != step.a || load.a != step.a || load.b != store.b ||
      load.c != store.c || at[3].op != Op::JLE_I)
    return std::nullopt;
  if (store.op == quickOpcode(QuickOp::ST_16) && load.op == quickOpcode(QuickOp::LD_I16)) return QuickOp::FOR_NEXT_I16;
  if (store.op == quickOpcode(QuickOp::ST_32) && load.op == quickOpcode(QuickOp::LD_I32)) return QuickOp::FOR_NEXT_I32;
  return std::nullopt;
}

}  // namespace

QuickCode quicken(const bc::Module& m, uint64_t memorySize) {
  QuickCode q{m.code, std::vector<EntryCheck>(m.pous.size())};
  const uint64_t guard = bc::Module::kNullGuard;
  for (size_t pou = 0; pou < m.pous.size(); ++pou) {
    const bc::PouInfo& p = m.pous[pou];
    if (!basesReadOnly(m, p)) continue;
    uint64_t extent[2] = {0, 0};  // fp, this
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
      const Instr& ins = m.code[pc];
      if (ins.b >= 2 || !quickForm(ins.op)) continue;
      const bool bit = ins.op == Op::LD_BIT || ins.op == Op::ST_BIT;  // C is the bit, not an offset
      extent[ins.b] = std::max<uint64_t>(extent[ins.b], (bit ? 0 : ins.c) + accessWidth(ins.op));
    }
    // Bases that can never pass the entry check (memory smaller than the extent): no quickening.
    if (std::max(extent[0], extent[1]) + guard > memorySize) continue;
    EntryCheck& e = q.entry[pou];
    e.lo = guard;
    if (extent[0]) e.fpSpan = memorySize - extent[0] - guard;
    if (extent[1]) e.thisSpan = memorySize - extent[1] - guard;
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
      Instr& ins = q.code[pc];
      if (ins.b < 2 && quickForm(ins.op)) ins.op = quickOpcode(*quickForm(ins.op));
    }
    const Instr* const end = q.code.data() + p.codeStart + p.codeSize;
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc)
      if (const std::optional<QuickOp> fused = forNextForm(&q.code[pc], end)) q.code[pc].op = quickOpcode(*fused);
  }
  for (const bc::PouInfo& p : m.pous)
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
      const Instr* next = pc + 1 < p.codeStart + p.codeSize ? &q.code[pc + 1] : nullptr;
      if (const std::optional<QuickOp> special = specialForm(m, q.code[pc], next)) q.code[pc].op = quickOpcode(*special);
    }
  return q;
}

}  // namespace virtcom::vm
