#pragma once
// Compiles PLCopen XML (and ST) files from tests/golden/plcopen and runs them scan by scan.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "lang/plcopen/exporter.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace virtcom::plcopen::testing {

inline const std::filesystem::path kGoldenDir = std::filesystem::path(VIRTCOM_SOURCE_DIR) / "tests" / "golden" / "plcopen";

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Inputs named like files: "x.xml" goes through the importer, anything else is ST.
inline st::SourceInput input(std::string path, std::string text) { return sourceInput(std::move(path), std::move(text)); }

struct Compiled {
  SourceManager sources;
  Diagnostics diags;
  std::unique_ptr<bc::Module> module;
  std::string rendered() const { return diags.render(sources); }
};

inline std::unique_ptr<Compiled> compile(const std::vector<st::SourceInput>& inputs) {
  auto c = std::make_unique<Compiled>();
  c->module = st::compileProgram(inputs, c->sources, c->diags);
  return c;
}

inline std::unique_ptr<Compiled> compileGolden(const std::string& name) {
  return compile({input(name, readFile(kGoldenDir / name))});
}

// The inputs parsed and exported as one TC6 project (no errors expected).
inline std::string exportOf(const std::vector<st::SourceInput>& inputs) {
  SourceManager sources;
  Diagnostics diags;
  st::NodeId next = 0;
  std::vector<st::CompilationUnit> units = st::parseInputs(inputs, sources, diags, next);
  std::vector<const st::CompilationUnit*> pointers;
  for (const auto& u : units) pointers.push_back(&u);
  std::string xml = exportProject(pointers, {}, diags);
  EXPECT_FALSE(diags.hasErrors()) << diags.render(sources);
  return xml;
}

// One PLC running a compiled program: set inputs, scan, read variables in IEC literal form.
class Plc {
 public:
  explicit Plc(const bc::Module& module) : module_(module), runtime_(module, clock_, options()) {
    EXPECT_TRUE(runtime_.coldStart()) << runtime_.faultText();
  }
  void set(const std::string& name, const std::string& value) {
    auto ref = bc::resolveVariable(module_, name);
    ASSERT_TRUE(ref) << "unknown variable " << name;
    ASSERT_EQ(bc::writeValueFromText(module_, *ref, value, runtime_.machine().memory()), "");
  }
  std::string get(const std::string& name) {
    auto ref = bc::resolveVariable(module_, name);
    if (!ref) return "<unknown " + name + ">";
    return bc::formatValue(module_, *ref, runtime_.machine().memory());
  }
  const uint8_t* memory() { return runtime_.machine().memory(); }
  void scan(int count = 1) {
    for (int k = 0; k < count; ++k) ASSERT_TRUE(runtime_.tick()) << runtime_.faultText();
  }

 private:
  static plc::RuntimeOptions options() {
    plc::RuntimeOptions o;
    o.instructionBudget = 1'000'000;
    return o;
  }
  const bc::Module& module_;
  VirtualClock clock_;
  plc::Runtime runtime_;
};

}  // namespace virtcom::plcopen::testing
