#pragma once
// Register liveness over the bytecode of one POU, for the peephole passes (peephole.hpp).
#include <cstdint>
#include <optional>
#include <vector>

#include "bytecode/instruction.hpp"

namespace virtcom::st {

// The lowest register an instruction writes and whether it writes every register from there up
// (a CALL's window; a CALLN writes A only); nullopt if it writes none.
struct RegisterWrite {
  uint16_t reg;
  bool andAbove;
};
std::optional<RegisterWrite> registerWrite(const bc::Instr& ins);
bool writesRegister(const bc::Instr& ins, uint16_t reg);

// The registers an instruction reads, as pointers into it (to rename them); a call also reads a
// register range that cannot be renamed: CALL A and A + 1 (the callee's fp and this, clipped to
// numRegs), CALLN A .. A + arity - 1.
struct RegisterReads {
  uint16_t* regs[3] = {};
  int count = 0;
  uint32_t windowFrom = 0, windowTo = 0;  // [from, to)
};
RegisterReads registerReads(bc::Instr& ins, uint16_t numRegs);

// Registers live before each instruction of code[begin, end): backward dataflow to a fixed
// point. At CALL the callee's r0 and r1 (A and A + 1) are live, nothing else of its window: the
// code generator passes parameters and results through memory, and a callee writes each of its
// registers before reading it. After RET only r0 and r1, and a caller reads nothing of the
// callee's window after the call but the frame pointer it set up itself.
class Liveness {
 public:
  Liveness(const std::vector<bc::Instr>& code, uint32_t begin, uint32_t end, uint16_t numRegs);

  // Whether `reg` is live before the instruction at absolute pc `pc` (begin <= pc < end).
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
  bool update(uint32_t k);

  const std::vector<bc::Instr>& code_;
  uint32_t begin_, n_, regs_, words_;
  std::vector<uint64_t> live_;
};

}  // namespace virtcom::st
