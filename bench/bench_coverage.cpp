// What code coverage costs when on (docs/coverage.md): the arithmetic and FB-call programs of
// bench/st compiled with and without coverage probes, on the interpreter and the AOT backend.
// docs/performance.md gives the ratios on/off measured in one run.
#include <benchmark/benchmark.h>

#include "st_program.hpp"

namespace virtcom::bench {
namespace {

void coverageScan(benchmark::State& state, const char* file, Backend backend, bool coverage) {
  StProgram prog(file, backend, coverage);
  if (!warmUp(state, prog, 1)) return;
  measureScans(state, prog);
}

BENCHMARK_CAPTURE(coverageScan, arithVmOff, "arith.st", Backend::Interp, false)->Name("coverage/arith/vm/off")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, arithVmOn, "arith.st", Backend::Interp, true)->Name("coverage/arith/vm/on")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, arithAotOff, "arith.st", Backend::Aot, false)->Name("coverage/arith/aot/off")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, arithAotOn, "arith.st", Backend::Aot, true)->Name("coverage/arith/aot/on")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, fbVmOff, "fb_calls.st", Backend::Interp, false)->Name("coverage/fb_calls/vm/off")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, fbVmOn, "fb_calls.st", Backend::Interp, true)->Name("coverage/fb_calls/vm/on")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, fbAotOff, "fb_calls.st", Backend::Aot, false)->Name("coverage/fb_calls/aot/off")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(coverageScan, fbAotOn, "fb_calls.st", Backend::Aot, true)->Name("coverage/fb_calls/aot/on")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
