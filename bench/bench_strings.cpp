// Benchmark (4): STRING functions (bench/st/strings.st) against a C++ twin on the same
// fixed-size, NUL-terminated buffers (STRING(80)), without allocation.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "st_program.hpp"

namespace virtcom::bench {
namespace {

using Str = std::array<char, 81>;  // STRING = STRING(80): 80 characters and the NUL

std::string_view view(const Str& s) { return {s.data(), std::strlen(s.data())}; }

void assign(Str& dst, std::string_view v) {
  const size_t n = std::min<size_t>(v.size(), dst.size() - 1);
  std::memmove(dst.data(), v.data(), n);
  dst[n] = '\0';
}

void concat(Str& dst, std::string_view a, std::string_view b) {
  Str tmp;
  const size_t na = std::min<size_t>(a.size(), tmp.size() - 1);
  const size_t nb = std::min<size_t>(b.size(), tmp.size() - 1 - na);
  std::memcpy(tmp.data(), a.data(), na);
  std::memcpy(tmp.data() + na, b.data(), nb);
  tmp[na + nb] = '\0';
  dst = tmp;
}

// MID(s, L, P) with the VM's rules: P < 1 or P > length gives '', L is clamped.
void mid(Str& dst, std::string_view s, int64_t len, int64_t pos) {
  if (pos < 1 || static_cast<size_t>(pos) > s.size() || len <= 0) return assign(dst, {});
  assign(dst, s.substr(static_cast<size_t>(pos - 1), static_cast<size_t>(len)));
}

int64_t find(std::string_view a, std::string_view b) {
  if (b.empty()) return 0;
  const size_t at = a.find(b);
  return at == std::string_view::npos ? 0 : static_cast<int64_t>(at) + 1;
}

void intToString(Str& dst, int64_t v) {
  auto [end, ec] = std::to_chars(dst.data(), dst.data() + dst.size() - 1, v);
  *end = '\0';
}

struct StringsProgram {
  Str s{}, t{}, u{};
  int32_t total = 0;
};

// Statement for statement strings.st (`base` = 37 is an input so nothing can be precomputed).
[[gnu::noinline]] void stringsScan(StringsProgram& p, int base) {
  Str num, tmp;
  p.total = 0;
  for (int i = 1; i <= 10; ++i) {
    intToString(num, i * base);
    concat(p.s, "Part-", view(num));
    concat(p.t, view(p.s), "/OK");
    assign(p.u, view(p.t).substr(0, 6));
    mid(tmp, view(p.t), 2, 3);
    p.total = p.total + static_cast<int32_t>(view(p.t).size() + find(view(p.t), "/") + view(tmp).size() +
                                             view(p.u).size());
    mid(p.s, view(p.t), 3, 4);
    if (find(view(p.s), "7") > 0) p.total = p.total + 100;
  }
}

void stringsVm(benchmark::State& state) {
  StProgram prog("strings.st");
  if (!warmUp(state, prog, 1)) return;
  StringsProgram twin;
  stringsScan(twin, 37);
  if (!expectValue(state, prog, "MAIN.total", twin.total) || !expectString(state, prog, "MAIN.s", view(twin.s)) ||
      !expectString(state, prog, "MAIN.t", view(twin.t)) || !expectString(state, prog, "MAIN.u", view(twin.u)))
    return;
  measureScans(state, prog);
}

void stringsNative(benchmark::State& state) {
  StringsProgram p;
  for (auto _ : state) {
    int base = 37;
    benchmark::DoNotOptimize(base);
    stringsScan(p, base);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(p.total);
  reportNative(state);
}

BENCHMARK(stringsVm)->Name("strings/vm")->Apply(withMinStatistic);
BENCHMARK(stringsNative)->Name("strings/native")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
