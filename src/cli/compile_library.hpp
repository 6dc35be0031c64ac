#pragma once
// Library mode of `virtcom check` and `export`: files holding only FUNCTIONs, FBs, types and
// global variable lists compile (every POU checked) instead of failing with E217 "no PROGRAM".
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::cli {

// Like compileFiles (diagnostics printed to stderr, null on a read or compile error), but a
// program without a PROGRAM is valid: the module then has no program instances.
std::unique_ptr<bc::Module> compileLibraryFiles(const std::vector<std::string>& paths, SourceManager& sources,
                                                Diagnostics& diags);

}  // namespace virtcom::cli
