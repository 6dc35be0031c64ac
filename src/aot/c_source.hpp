#pragma once
// Translates a verified bytecode module into C: one function per POU, every instruction
// expanded from aot/opcodes_c.def, split into translation units the C compiler handles
// separately (and in parallel, and caches one by one: aot/compile.cpp). The functions implement
// vm/compiled.hpp's AotEntry and work on the interpreter's memory image and register stack.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::aot {

// The exported symbols of a compiled module.
inline constexpr const char* kEntriesSymbol = "virtcom_aot_entries";
inline constexpr const char* kCountSymbol = "virtcom_aot_count";
inline constexpr const char* kAbiSymbol = "virtcom_aot_abi";

// A unit closes once its POUs hold this many instructions (a bigger POU gets a unit of its
// own). GCC's time and memory per unit grow faster than its size, and smaller units compile
// in parallel; but every unit repeats the prelude and a call into another unit is not
// inlined. docs/performance.md has the measurements behind the figure.
inline constexpr uint32_t kUnitInstructions = 4000;

struct CUnit {
  std::string source;        // a complete C translation unit
  uint32_t largestPou = 0;   // instructions of its largest POU (compile.cpp picks flags by it)
};

// The units for `m`, which must have passed bc::verifyModule; the last one holds the entry
// table. A POU's text does not depend on where other POUs sit in the code or on their index,
// and units end at boundaries chosen by the POUs' names, so an edit of one POU changes its own
// unit (and the table) and leaves the others' text alone, unless it changes what other POUs
// see of it (frame size, registers read; its register count is a constant of its own unit) or the memory size.
// What it reads from the module is what aot::moduleKey (module_key.hpp) hashes: a new input of
// the generator must go into that key too, or `--backend auto` could load another module's code.
std::vector<CUnit> generateCUnits(const bc::Module& m, uint32_t unitInstructions = kUnitInstructions);

}  // namespace virtcom::aot
