// Benchmark (3): ARRAY OF WORD sort, shifts, masks and bit access (bench/st/bits.st) against
// its C++ twin.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>

#include "st_program.hpp"

namespace virtcom::bench {
namespace {

// The PROGRAM instance of bits.st.
struct BitsProgram {
  std::array<uint16_t, 64> a{};
  int32_t bitCount = 0;
  uint16_t checksum = 0;
};

uint16_t rol16(uint16_t v, unsigned n) {
  n &= 15u;
  return n == 0 ? v : static_cast<uint16_t>((v << n) | (v >> (16u - n)));
}

bool bit(uint16_t w, unsigned n) { return ((w >> n) & 1u) != 0; }

// Statement for statement bits.st (the seed is an input so nothing can be precomputed).
[[gnu::noinline]] void bitsScan(BitsProgram& p, uint16_t seed) {
  for (int i = 0; i <= 63; ++i) {
    seed = static_cast<uint16_t>(seed * 25173u + 13849u);
    p.a[i] = seed;
  }
  for (int i = 1; i <= 63; ++i) {
    const uint16_t key = p.a[i];
    int j = i;
    while (j > 0) {
      if (p.a[j - 1] <= key) break;
      p.a[j] = p.a[j - 1];
      j = j - 1;
    }
    p.a[j] = key;
  }
  p.bitCount = 0;
  p.checksum = 0;
  for (int i = 0; i <= 63; ++i) {
    auto w = static_cast<uint16_t>((p.a[i] << 3) | (p.a[i] >> 13));
    w = static_cast<uint16_t>(w ^ (p.a[i] & 0x0F0Fu));
    if (bit(w, 3)) p.bitCount = p.bitCount + 1;
    if (bit(w, 15) && !bit(w, 0)) p.bitCount = p.bitCount + 2;
    w = bit(p.a[i], 2) ? static_cast<uint16_t>(w | 0x80u) : static_cast<uint16_t>(w & ~0x80u);
    p.a[i] = w;
    p.checksum = p.checksum ^ rol16(w, static_cast<unsigned>(i % 16));
  }
}

void bitsVm(benchmark::State& state, Backend backend) {
  StProgram prog("bits.st", backend);
  if (!warmUp(state, prog, 1)) return;
  BitsProgram twin;
  bitsScan(twin, 0x1234);
  if (!expectValue(state, prog, "MAIN.bitCount", twin.bitCount) ||
      !expectValue(state, prog, "MAIN.checksum", twin.checksum) || !expectValue(state, prog, "MAIN.a", twin.a))
    return;
  measureScans(state, prog);
}

void bitsNative(benchmark::State& state) {
  BitsProgram p;
  for (auto _ : state) {
    uint16_t seed = 0x1234;
    benchmark::DoNotOptimize(seed);
    bitsScan(p, seed);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(p.checksum);
  reportNative(state);
}

BENCHMARK_CAPTURE(bitsVm, interp, Backend::Interp)->Name("bits/vm")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(bitsVm, aot, Backend::Aot)->Name("bits/aot")->Apply(withMinStatistic);
BENCHMARK(bitsNative)->Name("bits/native")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
