// libFuzzer target: any bytes, compiled as the program file "fuzz.st", must give diagnostics or
// a verified module without crashing, hanging or leaking; every diagnostic must render. A module
// that comes out is cold-started and run for a few scans with a small instruction budget: a
// verified module may fault, but must never crash the VM.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace {
// Images beyond this are legal but only make the fuzzer slow (and hit its RSS limit).
constexpr uint64_t kMaxMemoryToRun = 64u << 20;
constexpr int kScans = 3;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<virtcom::st::SourceInput> inputs;
  inputs.push_back({"fuzz.st", std::string(reinterpret_cast<const char*>(data), size)});
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  auto module = virtcom::st::compileProgram(inputs, sources, diags);
  (void)diags.render(sources);
  if (!module || module->memorySize() > kMaxMemoryToRun) return 0;

  virtcom::VirtualClock clock;
  virtcom::plc::RuntimeOptions options;
  options.instructionBudget = 10'000;
  virtcom::plc::Runtime runtime(*module, clock, options);
  if (!runtime.coldStart()) {
    (void)runtime.faultText();
    return 0;
  }
  for (int k = 0; k < kScans; ++k)
    if (!runtime.tick()) break;
  (void)runtime.faultText();
  return 0;
}
