#pragma once
// Shared helpers of the activity-diagram tests: compiling diagram text (or ST, or PLCopen XML)
// into a program image and running it scan by scan.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "aot/compile.hpp"
#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace virtcom::ad::test {

// One source file: its path (whose extension selects the front end: .ad, .adxml, .xml, else
// ST) and its text.
using SourceFile = std::pair<std::string, std::string>;

// Compiles the files together as one program.
inline std::unique_ptr<bc::Module> compileFiles(const std::vector<SourceFile>& files, Diagnostics& diags) {
  SourceManager sources;
  std::vector<st::SourceInput> inputs;
  for (const auto& [path, text] : files) inputs.push_back(plcopen::sourceInput(path, text));
  return st::compileProgram(inputs, sources, diags);
}

inline std::unique_ptr<bc::Module> compileText(std::string path, std::string text, Diagnostics& diags) {
  return compileFiles({{std::move(path), std::move(text)}}, diags);
}

// "CODE line:col" of every diagnostic, one per line, for compact expectations.
inline std::string codesAndPlaces(const Diagnostics& diags) {
  std::string out;
  for (const Diagnostic& d : diags.all())
    out += std::string(d.code) + " " + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + "\n";
  return out;
}

// One compiled program on its own PLC runtime, its variables read and written by name below
// the PROGRAM `program`.
struct Side {
  std::string program = "P";
  std::unique_ptr<bc::Module> module;
  VirtualClock clock;
  std::unique_ptr<plc::Runtime> runtime;

  void write(const std::string& name, bool value) {
    auto ref = bc::resolveVariable(*module, program + "." + name);
    ASSERT_TRUE(ref) << name;
    uint8_t* memory = runtime->machine().memory();
    bc::writeValueFromText(*module, *ref, value ? "TRUE" : "FALSE", memory);
    // A located input (%IX) is read from the input image at the start of every scan.
    const bc::ProcessArea& in = module->inputs;
    if (ref->address >= in.address && ref->address < in.address + in.size)
      runtime->inputImage()[ref->address - in.address] = memory[ref->address];
    runtime->inputsTouched();
  }
  std::string read(const std::string& name) {
    auto ref = bc::resolveVariable(*module, program + "." + name);
    return ref ? bc::formatValue(*module, *ref, runtime->machine().memory()) : "<no " + name + ">";
  }
};

// Compiles the files and cold-starts them on the side's runtime; `native`: the program runs as
// machine code from the AOT backend instead of the interpreter.
inline void start(Side& side, const std::vector<SourceFile>& files, bool native = false) {
  Diagnostics diags;
  side.module = compileFiles(files, diags);
  ASSERT_NE(side.module, nullptr) << codesAndPlaces(diags) << (diags.all().empty() ? "" : diags.all()[0].message);
  side.runtime = std::make_unique<plc::Runtime>(*side.module, side.clock);
  if (native) {
    aot::CompileOptions options;
    options.cacheDir = VIRTCOM_AOT_TEST_CACHE;
    const aot::CompileResult compiled = aot::compileModule(*side.module, options);
    ASSERT_TRUE(compiled.code) << compiled.error;
    side.runtime->machine().useCompiled(compiled.code);
  }
  ASSERT_TRUE(side.runtime->coldStart());
}

inline void start(Side& side, std::string path, std::string text, bool native = false) {
  start(side, {{std::move(path), std::move(text)}}, native);
}

}  // namespace virtcom::ad::test
