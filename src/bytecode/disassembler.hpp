#pragma once
// Human-readable listings of bytecode; the compiler's golden tests compare this text, so the
// format is part of the contract:
//   MAIN (Program, 8 registers, frame 32 bytes @512)
//     0012  ADD      r3, r4, r5    ; MAIN.st:12:5
// One line per instruction: 4-digit absolute pc, opcode padded to 8, operands (registers rN,
// immediates in decimal, constants kN, absolute addresses @N, jump targets as absolute pcs,
// CALL/ENTER targets by POU name, CALLN by native name), and the source location on the
// instructions that start a statement. Works on unverified modules (bad operands are shown,
// not followed).
#include <cstdint>
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::bc {

// The listing of POU `pou` (header line plus one line per instruction, each ending in '\n');
// "" if pou is out of range. Allocates.
std::string disassemble(const Module& m, uint32_t pou);

// One instruction without the leading indentation and location: "ADD      r3, r4, r5".
std::string disassembleInstruction(const Module& m, uint32_t pc);

}  // namespace virtcom::bc
