#include "bytecode/memory_effects.hpp"

#include <algorithm>

#include "bytecode/verifier.hpp"

namespace virtcom::bc {

namespace {

uint32_t registerAccessWidth(Op op) {
  switch (op) {
    case Op::LD_I16: case Op::LD_U16: case Op::ST_16: case Op::STK_16: return 2;
    case Op::LD_I32: case Op::LD_U32: case Op::LD_F32: case Op::ST_32: case Op::ST_F32: case Op::STK_32: return 4;
    case Op::LD_64: case Op::ST_64: case Op::STK_64: return 8;
    default: return 1;
  }
}

}  // namespace

std::optional<MemoryRange> loadedRange(const Instr& ins) {
  switch (ins.op) {
    case Op::LD_BIT: return MemoryRange{false, ins.b, 0, 1};
    case Op::LD_I8: case Op::LD_U8: case Op::LD_I16: case Op::LD_U16: case Op::LD_I32: case Op::LD_U32:
    case Op::LD_64: case Op::LD_F32:
      return MemoryRange{false, ins.b, ins.c, registerAccessWidth(ins.op)};
    case Op::LDA_I8: case Op::LDA_U8: case Op::LDA_I16: case Op::LDA_U16: case Op::LDA_I32: case Op::LDA_U32:
    case Op::LDA_64: case Op::LDA_F32:
      return MemoryRange{true, 0, ins.bx(), operandRoles(ins.op).width};
    default: return std::nullopt;
  }
}

std::optional<MemoryRange> storedRange(const Instr& ins) {
  switch (ins.op) {
    case Op::ST_8: case Op::ST_16: case Op::ST_32: case Op::ST_64: case Op::ST_F32:
    case Op::STK_8: case Op::STK_16: case Op::STK_32: case Op::STK_64:
      return MemoryRange{false, ins.b, ins.c, registerAccessWidth(ins.op)};
    case Op::ST_BIT: return MemoryRange{false, ins.b, 0, 1};
    case Op::STA_8: case Op::STA_16: case Op::STA_32: case Op::STA_64: case Op::STA_F32:
      return MemoryRange{true, 0, ins.bx(), operandRoles(ins.op).width};
    case Op::CALLFB: return MemoryRange{false, ins.a, 0, nativeFbSize(static_cast<NativeFb>(ins.bx()))};
    default: return std::nullopt;
  }
}

bool writesBeyondRanges(Op op) {
  switch (op) {
    case Op::COPY: case Op::ENTER: case Op::CALL: case Op::CALLN: case Op::COVER: return true;
    default: return false;
  }
}

uint32_t nativeFbSize(NativeFb f) {
  uint32_t size = 0;
  for (const NativeFbMember& m : nativeFbMembers(f)) size = std::max(size, m.offset + m.size);
  return size;
}

bool basesReadOnly(const Module& m, const PouInfo& p) {
  const auto begin = m.code.begin() + p.codeStart;
  return std::none_of(begin, begin + p.codeSize, [](const Instr& ins) {
    const bool windowBelow2 = ins.op == Op::CALL || ins.op == Op::CALLN;
    return ins.a < 2 && (writesOnlyA(ins.op) || windowBelow2);
  });
}

std::vector<std::optional<Placed>> placedBases(const Module& m, const PouInfo& p) {
  const uint32_t n = p.codeSize;
  const Instr* const code = m.code.data() + p.codeStart;
  std::vector<bool> leader(n, false);
  for (uint32_t k = 0; k < n; ++k)
    if (isBranch(code[k].op)) {
      const int64_t target = branchTarget(k, code[k]);
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
    } else if (writesOnlyA(ins.op) && ins.a < p.numRegs) {
      address[ins.a] = placed;
      offset[ins.a] = index;
    }
  }
  return out;
}

std::optional<uint64_t> thisWriteReach(const Module& m, const PouInfo& p) {
  if (p.codeSize == 0 || !basesReadOnly(m, p)) return std::nullopt;
  const std::vector<std::optional<Placed>> placed = placedBases(m, p);
  uint64_t reach = 0;
  for (uint32_t k = 0; k < p.codeSize; ++k) {
    const Instr& ins = m.code[p.codeStart + k];
    // ENTER writes a callee's frame: stack above this POU's own.
    if (writesBeyondRanges(ins.op) && ins.op != Op::ENTER) return std::nullopt;
    const std::optional<MemoryRange> stored = storedRange(ins);
    if (!stored) continue;
    if (stored->absolute || !placed[k]) return std::nullopt;
    if (placed[k]->base == 1) reach = std::max(reach, placed[k]->reach + stored->offset + stored->width);
  }
  return reach;
}

}  // namespace virtcom::bc
