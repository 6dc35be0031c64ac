// Benchmark (1): DINT/REAL arithmetic loop (bench/st/arith.st) against its C++ twin.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "st_program.hpp"

namespace virtcom::bench {
namespace {

struct ArithResult {
  int32_t acc = 0;
  float racc = 0.0f;
  int32_t wraps = 0;
  int32_t evens = 0;
};

// Statement for statement arith.st. Not inlined, so it stays one call per scan like the POU.
[[gnu::noinline]] ArithResult arithNative(int32_t n) {
  ArithResult r;
  for (int32_t i = 1; i <= n; ++i) {
    r.acc = r.acc + (i * 7) % 13 + i / 9;
    if (i % 3 == 0) r.acc = r.acc - i;
    else r.acc = r.acc + 2 * i;
    r.racc = r.racc + static_cast<float>(i) * 0.375f;
    if (r.racc > 500.0f) {
      r.racc = r.racc - 499.5f;
      r.wraps = r.wraps + 1;
    }
    if (r.acc % 2 == 0 && r.racc < 250.0f) r.evens = r.evens + 1;
  }
  return r;
}

void arithVm(benchmark::State& state, Backend backend) {
  StProgram prog("arith.st", backend);
  if (!warmUp(state, prog, 1)) return;
  const ArithResult want = arithNative(1000);
  if (!expectValue(state, prog, "MAIN.acc", want.acc) || !expectValue(state, prog, "MAIN.racc", want.racc) ||
      !expectValue(state, prog, "MAIN.wraps", want.wraps) || !expectValue(state, prog, "MAIN.evens", want.evens))
    return;
  measureScans(state, prog);
}

void arithNativeBench(benchmark::State& state) {
  for (auto _ : state) {
    int32_t n = 1000;
    benchmark::DoNotOptimize(n);  // the trip count is opaque: the loop cannot be folded away
    ArithResult r = arithNative(n);
    benchmark::DoNotOptimize(r);
  }
  reportNative(state);
}

BENCHMARK_CAPTURE(arithVm, interp, Backend::Interp)->Name("arith/vm")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(arithVm, aot, Backend::Aot)->Name("arith/aot")->Apply(withMinStatistic);
BENCHMARK(arithNativeBench)->Name("arith/native")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
