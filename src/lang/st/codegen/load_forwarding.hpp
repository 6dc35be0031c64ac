#pragma once
// Redundant-load elimination over the bytecode of one POU, a peephole pass (peephole.hpp).
#include <cstdint>
#include <vector>

#include "bytecode/instruction.hpp"
#include "bytecode/module.hpp"

namespace virtcom::st {

// Finds the loads in m.code[begin, end) whose value a register already holds on every path that
// reaches them (the same load from the same base register and offset, with no store and no call
// that may write it, and no write of either register in between), and likewise the pure
// computations (INDEX, arithmetic, LDI/LDK) on unchanged operands, and the copies (MOV, and a
// SEXT/ZEXT of a register already in that form) of a register; renames their destination to
// that register in the instructions that read it before it is written again, and returns which
// instructions (by index from begin) are now dead and to be removed. A load is kept when its
// register is still read after its basic block, or the holding register is written before the
// last read. Branch offsets are left as they are. A call of a POU compiled before (its code in m)
// that writes nothing but its own frame and instance (bc::thisWriteReach) keeps the loads of the
// caller's frame, instance and globals outside that instance; any other call keeps no load.
std::vector<bool> forwardLoads(bc::Module& m, uint32_t begin, uint32_t end, uint16_t numRegs);

}  // namespace virtcom::st
