#pragma once
// A peephole pass over the bytecode of one POU, run right after its code generation.
#include <cstddef>
#include <cstdint>

#include "bytecode/module.hpp"

namespace virtcom::st {

// Rewrites m.code[codeStart, m.code.size()) -- the POU just generated, ending with its RET -- in
// place, and renumbers the line entries m.lines[firstLine, m.lines.size()) that point into it:
// first a load or pure computation whose value a register already holds is removed and its
// readers read that register (load_forwarding.hpp), repeated until nothing more goes; then a
// loop's constants are loaded once before it (loop_constants.hpp); then a comparison whose
// result only feeds the next JZ/JNZ becomes one fused compare-and-branch (JEQ .. JGEK), and
// LNOT + JZ/JNZ a JNZ/JZ.
// `numRegs` is the POU's register window; returns the new one (a loop's constant may get a
// register of its own). Results, faults (kind, file:line:col) and the
// watchdog's events (taken backward jumps, calls) stay the same; only the number of
// instructions changes.
uint16_t optimizePou(bc::Module& m, uint32_t codeStart, size_t firstLine, uint16_t numRegs);

}  // namespace virtcom::st
