// Issue 21: the cost of a tick as the cell grows. The generated cell of N stations
// (scaling_cell.hpp, 4 devices each) runs for 60 s of virtual time with a 10 ms task; counters:
// CPU ns per device per tick and the real-time factor. Loading is outside the timing.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "cell/cell.hpp"
#include "scaling_cell.hpp"
#include "sim/simulation.hpp"

namespace virtcom::bench {
namespace {

constexpr int64_t kTaskNs = 10'000'000;
constexpr int64_t kVirtualNs = 60'000'000'000;

void BM_CellScaling(benchmark::State& state) {
  const int stations = static_cast<int>(state.range(0));
  std::string error;
  const std::string dir = (std::filesystem::temp_directory_path() / ("virtcom-scaling-" + std::to_string(stations))).string();
  const std::string path = writeScalingCell(dir, stations, kTaskNs, error);
  if (path.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  uint64_t ticks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    SourceManager sources;
    Diagnostics diags;
    auto cell = cell::loadCell(path, sources, diags);
    if (!cell) {
      state.SkipWithError(diags.render(sources).c_str());
      return;
    }
    sim::SimOptions options;
    options.timeLimitNs = kVirtualNs;
    options.keepAllChanges = false;
    sim::Simulation simulation(*cell, options);
    state.ResumeTiming();
    simulation.run();
    state.PauseTiming();
    if (simulation.trace().end != RunEnd::TimeLimit) state.SkipWithError(simulation.trace().endMessage.c_str());
    ticks = simulation.ticks();
    state.ResumeTiming();
  }
  const double devices = static_cast<double>(stations) * kDevicesPerStation;
  state.counters["devices"] = devices;
  state.counters["ns_per_device_tick"] = benchmark::Counter(
      devices * static_cast<double>(ticks) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["realtime_factor"] = benchmark::Counter(
      static_cast<double>(kVirtualNs) * 1e-9 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_CellScaling)->Name("scaling/stations")->Arg(1)->Arg(8)->Arg(32)->Arg(128)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace virtcom::bench
