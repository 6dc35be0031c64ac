#pragma once
// Warm start: the RETAIN and PERSISTENT variables (globals, and members of program instances)
// are saved to a text file when a run ends cleanly and loaded after the cold start of the next
// run, so they survive a restart. One line per variable, `NAME HEX TYPE`:
//   MAIN.count 2a000000 DINT
// A line whose variable no longer exists, or whose type name or size changed, is skipped: that
// variable keeps its initial value (as CODESYS does when the retain layout changed).
#include <cstdint>
#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::plc {

struct RetainedVariable {
  std::string name;  // "GVL.x", "MAIN.count"
  bc::TypeId type = bc::kNoType;
  uint32_t address = 0;
};

// Every RETAIN/PERSISTENT variable of the module, globals first.
std::vector<RetainedVariable> retainedVariables(const bc::Module& m);

// Loads `path` into `memory`. A missing file is not an error (the first run): 0 variables.
// `restored` counts the variables loaded. Empty on success, else why the file cannot be read.
// (The clang-19 fuzz build compiles this library too: tests/fuzz/fuzz_retain_file.cpp.)
std::string loadRetainFile(const std::string& path, const bc::Module& m, uint8_t* memory, size_t& restored);
// The same over the file's text already open as `in`; `path` names it in the error text (the
// fuzz target feeds it mutated files).
std::string loadRetainText(std::istream& in, const std::string& path, const bc::Module& m, uint8_t* memory, size_t& restored);

// Writes the retained variables of `memory` to `path` (replacing it). Empty on success.
std::string saveRetainFile(const std::string& path, const bc::Module& m, const uint8_t* memory);

}  // namespace virtcom::plc
