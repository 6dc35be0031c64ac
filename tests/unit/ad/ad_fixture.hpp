#pragma once
// Shared helpers of the activity-diagram tests: reading .ad text and compiling it (or ST) into
// a program image.
#include <memory>
#include <string>
#include <string_view>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/ad/lower.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::ad::test {

// Compiles one file: `.ad` files through the diagram front end, others as ST.
inline std::unique_ptr<bc::Module> compileText(std::string path, std::string text, Diagnostics& diags) {
  SourceManager sources;
  st::SourceInput input{path, std::move(text)};
  if (path.ends_with(".ad")) input.frontEnd = importDiagrams;
  return st::compileProgram({input}, sources, diags);
}

// "CODE line:col" of every diagnostic, one per line, for compact expectations.
inline std::string codesAndPlaces(const Diagnostics& diags) {
  std::string out;
  for (const Diagnostic& d : diags.all())
    out += std::string(d.code) + " " + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + "\n";
  return out;
}

}  // namespace virtcom::ad::test
