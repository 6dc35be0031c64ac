#pragma once
// A cheap key for a module's machine code: what lets `--backend auto` find a former run's shared
// object before the first scan without generating the C (which costs more than a short run).
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::aot {

// A hash of everything the C generator (aot/c_source.hpp) reads from `m` (the code, constants and
// index descriptors, each POU's name, code range and register count, the memory sizes), the
// unit size, the ABI version and the build id of the binary this generator is part of (so a
// rebuilt generator never meets an old key). Empty when the binary has no build id: then only
// compileModule's key, from the generated C, finds cached code.
std::string moduleKey(const bc::Module& m, uint32_t unitInstructions);

}  // namespace virtcom::aot
