#pragma once
// The ST compiler's entry point: source files in, a verified program image out.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::st {

// Turns one registered file into a syntax tree, like parseFile() (e.g. the PLCopen XML importer).
using FrontEnd = std::function<CompilationUnit(uint32_t fileId, std::string_view text, Diagnostics& diags,
                                               NodeId& nextNodeId)>;

struct SourceInput {
  std::string path;  // shown in diagnostics; its stem names a file's global variable list
  std::string text;
  FrontEnd frontEnd = {};  // empty: the file is Structured Text
};

// Registers and parses every input with its front end; a file's unnamed VAR_GLOBAL lists are
// named after its stem. Diagnostics go to `diags`. Never throws on bad input.
std::vector<CompilationUnit> parseInputs(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                         Diagnostics& diags, NodeId& nextNodeId);

struct CompileOptions {
  // Library mode (`virtcom check`, `export`): files holding only FUNCTIONs, FBs, types and
  // global variable lists compile (every POU is checked) instead of failing with E217.
  bool library = false;
  // Code coverage (docs/coverage.md): a COVER probe at every statement of the user's POUs, at
  // the entry of every IF/CASE arm (the implicit ELSE included) and at every SFC step activation
  // and transition firing, counting in module.coverage's counters. Off, the code is exactly the
  // code compiled without this option.
  bool coverage = false;
  // The folder of compiled modules (lang/st/compile_cache.hpp); empty: compile every time.
  // A member added here must also go into moduleCacheKey.
  std::string cacheDir;
};

// Default options with coverage probes on or off.
inline CompileOptions coverageOptions(bool coverage) {
  CompileOptions options;
  options.coverage = coverage;
  return options;
}

// Compiles every file as one program (plus the standard library). All diagnostics go to `diags`
// (sorted by location); the sources are registered in `sources`. Returns the module, or null if
// there was any error. Never throws on bad input. With `options.cacheDir`, a former compile of
// the same inputs is read back instead, and a compile without diagnostics is kept.
std::unique_ptr<bc::Module> compileProgram(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                           Diagnostics& diags, CompileOptions options = {});

}  // namespace virtcom::st
