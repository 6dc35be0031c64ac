#pragma once
// What the protocol benchmarks of virtcom_ads_bench share (bench_ads.cpp, bench_opcua.cpp): the
// PLC both servers serve, and the figures a round trip is judged by.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include "proto/ads/symbol_table.hpp"

namespace virtcom::bench {

inline constexpr uint32_t kVariables = 100;
inline constexpr uint32_t kFirstOffset = 64;

// MAIN.v0..MAIN.v99: DINTs at 64, 68, ... in a 1 KB data area.
inline const proto::ads::SymbolTable& table() {
  namespace ads = proto::ads;
  static const ads::SymbolTable t = [] {
    std::vector<ads::Symbol> symbols;
    for (uint32_t i = 0; i < kVariables; ++i)
      symbols.push_back({"MAIN.v" + std::to_string(i), "DINT", 0x4040, kFirstOffset + 4 * i, 4, ads::adst::kInt32, 0});
    auto resolver = [symbols](std::string_view path) -> std::optional<ads::Symbol> {
      for (const auto& s : symbols)
        if (ads::lowerCase(s.name) == ads::lowerCase(path)) return s;
      return std::nullopt;
    };
    return ads::SymbolTable(symbols, {{"DINT", "", 4, ads::adst::kInt32, ads::kTypeFlagDataType, {}, {}, {}}},
                            {1024, {0, 16}, {16, 16}, {32, 16}, {}}, resolver);
  }();
  return t;
}

// The round trips of one benchmark run, for the median and the 99th percentile (the mean that
// Google Benchmark reports hides the tail the issue asks about). Bench code only: it reads the clock.
class RoundTrips {
 public:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start() const { return Clock::now(); }
  void stop(Clock::time_point started) {
    ns_.push_back(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
  }
  void report(benchmark::State& state) {
    if (ns_.empty()) return;
    std::sort(ns_.begin(), ns_.end());
    state.counters["p50_us"] = static_cast<double>(ns_[ns_.size() / 2]) / 1000.0;
    state.counters["p99_us"] = static_cast<double>(ns_[ns_.size() * 99 / 100]) / 1000.0;
  }

 private:
  std::vector<int64_t> ns_;
};

// CPU time of the whole process (client and server threads) over a benchmark run, per item:
// the counter cpu_us_per_item, which the machine's load does not inflate as it does real time.
class ProcessCpu {
 public:
  ProcessCpu() : startNs_(nowNs()) {}
  void report(benchmark::State& state, double items) const {
    if (items > 0) state.counters["cpu_us_per_item"] = static_cast<double>(nowNs() - startNs_) / 1000.0 / items;
  }

 private:
  static int64_t nowNs() {
    timespec t{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
  }
  int64_t startNs_;
};

}  // namespace virtcom::bench
