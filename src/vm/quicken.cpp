#include "vm/quicken.hpp"

#include <algorithm>
#include <optional>

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

// Where the base register of an access points: `reach` bytes or less past fp (base 0) or this
// (base 1), never before it.
struct Placed {
  uint16_t base;
  uint64_t reach;
};

// For each instruction of POU `p` (whose r0 and r1 nothing writes), where its B register points
// if it is fp, this, or an address computed from them in the same basic block: an array element
// (ADD of fp/this and an INDEX, at most IndexDesc::lastOffset past them), a member at a constant
// offset (ADDI of a non-negative constant), or both (a member of an element, an FB instance in an
// array). The element's accesses can then skip checkedAddress like the
// direct ones, their reach added to the extent that the entry check proves.
std::vector<std::optional<Placed>> placedBases(const bc::Module& m, const bc::PouInfo& p) {
  const uint32_t n = p.codeSize;
  const Instr* const code = m.code.data() + p.codeStart;
  std::vector<bool> leader(n, false);
  for (uint32_t k = 0; k < n; ++k)
    if (bc::isBranch(code[k].op)) {
      const int64_t target = bc::branchTarget(k, code[k]);
      if (target >= 0 && target < n) leader[target] = true;
    }
  std::vector<std::optional<Placed>> out(n);
  std::vector<std::optional<Placed>> address(p.numRegs);     // an address past fp or this
  std::vector<std::optional<uint64_t>> offset(p.numRegs);    // an INDEX result, at most this
  for (uint32_t k = 0; k < n; ++k) {
    if (leader[k]) {
      std::fill(address.begin(), address.end(), std::nullopt);
      std::fill(offset.begin(), offset.end(), std::nullopt);
    }
    const Instr& ins = code[k];
    const uint16_t base = ins.op == Op::CALLFB ? ins.a : ins.b;  // the instance, or the access's base
    if (base < 2) out[k] = Placed{base, 0};
    else if (base < p.numRegs) out[k] = address[base];
    std::optional<Placed> placed;
    std::optional<uint64_t> index;
    if (ins.op == Op::INDEX && ins.c < m.indexes.size()) {
      index = m.indexes[ins.c].lastOffset();
    } else if (ins.op == Op::ADD && ins.b < p.numRegs && ins.c < p.numRegs) {
      if (ins.b < 2 && offset[ins.c]) placed = Placed{ins.b, *offset[ins.c]};
      else if (ins.c < 2 && offset[ins.b]) placed = Placed{ins.c, *offset[ins.b]};
    } else if (ins.op == Op::ADDI && ins.b < p.numRegs && static_cast<int16_t>(ins.c) >= 0) {
      const auto constant = static_cast<uint64_t>(static_cast<int16_t>(ins.c));
      if (ins.b < 2) placed = Placed{ins.b, constant};
      else if (address[ins.b]) placed = Placed{address[ins.b]->base, address[ins.b]->reach + constant};
    }
    if (ins.op == Op::CALL || ins.op == Op::CALLN) {  // a callee may write its whole window
      for (uint32_t r = ins.a; r < p.numRegs; ++r) {
        address[r] = std::nullopt;
        offset[r] = std::nullopt;
      }
    } else if (bc::writesOnlyA(ins.op) && ins.a < p.numRegs) {
      address[ins.a] = placed;
      offset[ins.a] = index;
    }
  }
  return out;
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
  QuickCode q{m.code, std::vector<EntryCheck>(m.pous.size())};
  const uint64_t guard = bc::Module::kNullGuard;
  for (size_t pou = 0; pou < m.pous.size(); ++pou) {
    const bc::PouInfo& p = m.pous[pou];
    if (!basesReadOnly(m, p)) continue;
    // Each access with a placed base, and how far past fp or this it may reach; one whose reach
    // memory could never hold stays checked (its fault is then the program's).
    const std::vector<std::optional<Placed>> placed = placedBases(m, p);
    std::vector<bool> quick(p.codeSize, false);
    uint64_t extent[2] = {0, 0};  // fp, this
    for (uint32_t k = 0; k < p.codeSize; ++k) {
      const Instr& ins = m.code[p.codeStart + k];
      const bool fb = ins.op == Op::CALLFB && ins.bx() < kNativeFbSizes.size();
      if (!placed[k] || !(quickForm(ins.op) || fb)) continue;
      const bool bit = ins.op == Op::LD_BIT || ins.op == Op::ST_BIT;  // C is the bit, not an offset
      const uint64_t reach = placed[k]->reach + (fb ? kNativeFbSizes[ins.bx()] : (bit ? 0 : ins.c) + accessWidth(ins.op));
      if (reach + guard > memorySize) continue;
      quick[k] = true;
      extent[placed[k]->base] = std::max(extent[placed[k]->base], reach);
    }
    EntryCheck& e = q.entry[pou];
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
  for (const bc::PouInfo& p : m.pous)
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
      const Instr* next = pc + 1 < p.codeStart + p.codeSize ? &q.code[pc + 1] : nullptr;
      if (const std::optional<QuickOp> special = specialForm(m, q.code[pc], next)) q.code[pc].op = quickOpcode(*special);
    }
  return q;
}

}  // namespace virtcom::vm
