#pragma once
// The C statements of every opcode (aot/opcodes_c.def) and which registers they read and
// write, read off the very text that is emitted, so the two cannot disagree.
#include <string_view>

#include "bytecode/instruction.hpp"

namespace virtcom::aot {

// The statements of `op` with their %-placeholders (see opcodes_c.def).
std::string_view opcodeSnippet(bc::Op op);

// How an opcode's snippet uses the registers A, B and C. A counts as written only if every
// %A in it is the target of an assignment ("%A = "); any other %A reads it.
struct RegisterAccess {
  bool readsA = false;
  bool writesA = false;
  bool readsB = false;
  bool readsC = false;
};
RegisterAccess registerAccess(bc::Op op);

}  // namespace virtcom::aot
