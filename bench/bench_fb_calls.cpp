// Benchmark (2): 100 TON + 100 CTU + 100 user FB calls per scan (bench/st/fb_calls.st)
// against its C++ twin.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>

#include "native_fbs.hpp"
#include "st_program.hpp"

namespace virtcom::bench {
namespace {

constexpr int64_t kScanNs = 10'000'000;  // the default task's interval
constexpr int kVerifyScans = 200;         // long enough for every counter to wrap at PV

// FB_Filter from fb_calls.st.
struct NativeFilter {
  float x = 0.0f;
  bool enable = false;
  float y = 0.0f;
  bool high = false;

  void call() {
    if (enable) y = y + (x - y) * 0.125f;
    else y = 0.0f;
    high = y > 5.0f;
  }
};

// The PROGRAM instance of fb_calls.st: FB instances and outputs live in memory between scans.
struct FbCallsProgram {
  std::array<NativeTon, 100> timers;
  std::array<NativeCtu, 100> counters;
  std::array<NativeFilter, 100> filters;
  int32_t qCount = 0;
  int32_t cvSum = 0;
  int32_t highCount = 0;
  float ySum = 0.0f;
};

// One scan of fb_calls.st's MAIN at task time `nowNs` (index i + 1 is the ST index).
[[gnu::noinline]] void fbCallsScan(FbCallsProgram& p, int64_t nowNs) {
  p.qCount = 0;
  p.cvSum = 0;
  p.highCount = 0;
  p.ySum = 0.0f;
  for (int i = 1; i <= 100; ++i) {
    NativeTon& t = p.timers[i - 1];
    NativeCtu& c = p.counters[i - 1];
    NativeFilter& f = p.filters[i - 1];
    t.in = !t.q;
    t.ptMs = (i % 5 + 1) * 10;
    t.call(nowNs);
    c.cu = t.q;
    c.reset = c.q;
    c.pv = 10;
    c.call();
    if (c.q) p.qCount = p.qCount + 1;
    p.cvSum = p.cvSum + c.cv;
    f.x = static_cast<float>(c.cv);
    f.enable = true;
    f.call();
    if (f.high) p.highCount = p.highCount + 1;
    p.ySum = p.ySum + f.y;
  }
}

void fbCallsVm(benchmark::State& state, Backend backend) {
  StProgram prog("fb_calls.st", backend);
  if (!warmUp(state, prog, kVerifyScans)) return;
  FbCallsProgram twin;
  for (int k = 0; k < kVerifyScans; ++k) fbCallsScan(twin, k * kScanNs);
  if (!expectValue(state, prog, "MAIN.qCount", twin.qCount) || !expectValue(state, prog, "MAIN.cvSum", twin.cvSum) ||
      !expectValue(state, prog, "MAIN.highCount", twin.highCount) || !expectValue(state, prog, "MAIN.ySum", twin.ySum))
    return;
  measureScans(state, prog);
}

void fbCallsNative(benchmark::State& state) {
  FbCallsProgram p;
  int64_t nowNs = 0;
  for (auto _ : state) {
    fbCallsScan(p, nowNs);
    benchmark::ClobberMemory();
    nowNs += kScanNs;
  }
  benchmark::DoNotOptimize(p.ySum);
  reportNative(state);
}

BENCHMARK_CAPTURE(fbCallsVm, interp, Backend::Interp)->Name("fb_calls/vm")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(fbCallsVm, aot, Backend::Aot)->Name("fb_calls/aot")->Apply(withMinStatistic);
BENCHMARK(fbCallsNative)->Name("fb_calls/native")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
