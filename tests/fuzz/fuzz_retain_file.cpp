// libFuzzer target for the retain file (exec --retain-file: `NAME HEX TYPE` lines, read at a warm
// start from a file anyone with access to the directory may have edited): any bytes, loaded into
// the memory of a program with RETAIN and PERSISTENT variables of several types and sizes, must
// give an error text or restored variables, never a write outside a variable's bytes. The memory
// lies in its own allocation with a canary after it, so ASan sees any overrun.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "plc/retain_file.hpp"

namespace {

constexpr const char* kProgram = R"(
VAR_GLOBAL RETAIN
  count : DINT;
  flags : ARRAY[0..3] OF BOOL;
  name : STRING[8];
END_VAR
VAR_GLOBAL PERSISTENT
  position : LREAL;
END_VAR
PROGRAM MAIN
VAR RETAIN
  total : ULINT;
  state : INT;
END_VAR
  state := state + 1;
END_PROGRAM
)";

const virtcom::bc::Module& program() {
  static const std::unique_ptr<virtcom::bc::Module> module = [] {
    virtcom::SourceManager sources;
    virtcom::Diagnostics diags;
    auto m = virtcom::st::compileProgram({{"retain.st", kProgram}}, sources, diags);
    if (!m) __builtin_trap();  // the fixed program must compile
    return m;
  }();
  return *module;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const virtcom::bc::Module& m = program();
  std::vector<uint8_t> memory(m.memorySize());
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  size_t restored = 0;
  std::string problem = virtcom::plc::loadRetainText(in, "fuzz.retain", m, memory.data(), restored);
  if (!problem.empty() && problem.rfind("fuzz.retain:", 0) != 0) __builtin_trap();  // errors name the file and line
  return 0;
}
