#pragma once
// Loop-invariant constants, a step of the peephole pass (peephole.hpp). Code generation loads a
// constant into a register at every use (`LDI r8, 7` for `i * 7`), so a loop body loads the same
// constants again on every iteration; a constant whose register holds nothing else in the loop
// can be loaded once, before it.
#include <cstdint>
#include <optional>
#include <vector>

#include "bytecode/instruction.hpp"

namespace virtcom::st {

// What to move for one loop: the constant loads `moved` (indices from codeStart, in code order)
// go right before the loop's first instruction `head`, and the loads `dropped` (a repeat of a
// moved one: same register, same constant) go.
struct LoopConstants {
  uint32_t head = 0;
  std::vector<uint32_t> moved, dropped;
};

// The first loop of code[codeStart, end) with constants to move; nullopt if none. A loop is the
// range from a backward branch's target (the head) to its last backward branch there, entered only
// by falling into its head. An LDI or LDK in it moves when its register (r2 and up) is written in
// the loop by nothing but the same load (no call's window covers it) and is not live at the head:
// every read of it in the loop then reads that constant, and nothing after the loop read the
// register's earlier value. A load whose register also holds other values is first given a
// register of its own, numRegs (which grows, up to maxRegs), when all that reads its value follows
// it in its basic block and no call in the loop may overwrite that register: those instructions
// are renamed in `code`. `target` holds the branch targets by index (-1: no branch).
std::optional<LoopConstants> takeLoopConstants(std::vector<bc::Instr>& code, uint32_t codeStart, uint32_t end,
                                               const std::vector<int64_t>& target, uint16_t& numRegs, uint16_t maxRegs);

}  // namespace virtcom::st
