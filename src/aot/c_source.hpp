#pragma once
// Translates a verified bytecode module into C source: one function per POU, every
// instruction expanded from aot/opcodes_c.def. The functions implement vm/compiled.hpp's
// AotEntry and work on the interpreter's memory image and register stack.
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::aot {

// The exported symbols of a compiled module.
inline constexpr const char* kEntriesSymbol = "virtcom_aot_entries";
inline constexpr const char* kCountSymbol = "virtcom_aot_count";
inline constexpr const char* kAbiSymbol = "virtcom_aot_abi";

// The whole translation unit for `m`, which must have passed bc::verifyModule.
std::string generateCSource(const bc::Module& m);

}  // namespace virtcom::aot
