#pragma once
// The ST compiler's entry point: source files in, a verified program image out.
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::st {

struct SourceInput {
  std::string path;  // shown in diagnostics; its stem names a file's global variable list
  std::string text;
};

// Compiles every file as one program (plus the standard library). All diagnostics go to `diags`
// (sorted by location); the sources are registered in `sources`. Returns the module, or null if
// there was any error. Never throws on bad input.
std::unique_ptr<bc::Module> compileProgram(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                           Diagnostics& diags);

}  // namespace virtcom::st
