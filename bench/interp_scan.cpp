// virtcom_interp_scan FILE.st SCANS [aot|count]: compiles FILE.st, cold starts it on the
// interpreter (or, with `aot`, on the AOT backend's machine code; every scan executed, 10 ms
// virtual task), runs SCANS scans and prints the VM instructions per scan (counted with `count`
// only, as counting costs an x86 instruction per VM instruction; else 0) and an FNV-1a hash of
// the memory image after the last scan. bench/interp_counts.sh and bench/aot_counts.sh run it
// under callgrind (x86 instructions per Runtime::tick or per call of the compiled MAIN, exactly
// SCANS calls), and interp_counts.sh again with `count`; equal hashes before and after a change,
// and between the backends, show the same results. Links only the compiler, the runtime and the AOT backend, so it builds in a fraction
// of virtcom_bench's time.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "aot/compile.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

int main(int argc, char** argv) {
  using namespace virtcom;
  const bool aotBackend = argc == 4 && std::string_view(argv[3]) == "aot";
  const bool counting = argc == 4 && std::string_view(argv[3]) == "count";
  if (argc != 3 && !aotBackend && !counting) {
    std::fprintf(stderr, "usage: virtcom_interp_scan FILE.st SCANS [aot|count]\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({st::SourceInput{argv[1], text.str()}}, sources, diags);
  if (!module) {
    std::fprintf(stderr, "%s", diags.render(sources).c_str());
    return 1;
  }
  VirtualClock clock;
  plc::RuntimeOptions options;
  options.skipRepeatedScans = false;
  plc::Runtime runtime(*module, clock, options);
  if (aotBackend) {
    aot::CompileResult compiled = aot::compileModule(*module);
    if (!compiled.code) {
      std::fprintf(stderr, "AOT backend: %s\n", compiled.error.c_str());
      return 1;
    }
    runtime.machine().useCompiled(compiled.code);
  }
  runtime.machine().countInstructions(counting);
  const long scans = std::strtol(argv[2], nullptr, 10);
  bool ok = runtime.coldStart();
  const uint64_t before = runtime.machine().instructionsExecuted();
  for (long i = 0; ok && i < scans; ++i) ok = runtime.tick();
  if (!ok) {
    std::fprintf(stderr, "fault: %s\n", runtime.faultText().c_str());
    return 1;
  }
  uint64_t hash = 14695981039346656037ull;
  const uint8_t* mem = runtime.machine().memory();
  for (uint32_t i = 0; i < runtime.machine().memorySize(); ++i) hash = (hash ^ mem[i]) * 1099511628211ull;
  std::printf("vm_instr_per_scan %.1f\nmemory_hash %016llx\n",
              static_cast<double>(runtime.machine().instructionsExecuted() - before) / static_cast<double>(scans),
              static_cast<unsigned long long>(hash));
  return 0;
}
