// Whole-scenario benchmark: one full assembly cycle of the bundled gearbox cell
// (examples/gearbox-cell, sequence 1 = the longest) with its PLC task at 1 ms, as issue 4
// requires. Reports the simulated seconds per wall second (the real-time factor).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cell/cell.hpp"
#include "history/recorder.hpp"
#include "sim/simulation.hpp"

namespace virtcom::bench {
namespace {

// Loads the gearbox cell with the PLC task interval set to `cycleNs`.
std::unique_ptr<cell::Cell> loadGearbox(int64_t cycleNs, SourceManager& sources, Diagnostics& diags) {
  auto cell = cell::loadCell(VIRTCOM_GEARBOX_CELL, sources, diags);
  if (!cell) return nullptr;
  cell->run.plcCycleNs = cycleNs;
  for (auto& t : cell->module->tasks) t.intervalNs = cycleNs;
  return cell;
}

// `historyPath`: also record the run there (--history), from a new file each iteration.
// `eventTime` false steps every tick (--time-mode tick), the reference for event-driven time.
void runGearbox(benchmark::State& state, int64_t cycleNs, bool skipRepeatedScans, const std::string& historyPath = {},
                bool eventTime = true) {
  double simulatedS = 0;
  double vmInstructions = 0;  // interpreter instructions over all cycles (bench/interp_counts.sh)
  for (auto _ : state) {
    state.PauseTiming();
    SourceManager sources;
    Diagnostics diags;
    auto cell = loadGearbox(cycleNs, sources, diags);
    if (!cell) {
      state.SkipWithError(diags.render(sources).c_str());
      return;
    }
    sim::SimOptions options;
    options.skipRepeatedScans = skipRepeatedScans;
    options.eventTime = eventTime;
    options.preset = [](plc::Runtime& plc) {
      auto ref = bc::resolveVariable(plc.module(), "MAIN.sequence");
      bc::writeValueFromText(plc.module(), *ref, "1", plc.machine().memory());
    };
    std::unique_ptr<history::Recorder> recorder;
    if (!historyPath.empty()) {
      for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(historyPath + suffix);
      history::RecorderOptions recording;
      recording.waitWhenFull = true;  // as `virtcom run` in virtual time: everything recorded
      auto opened = history::Recorder::open(historyPath, recording);
      if (!opened) {
        state.SkipWithError(opened.error().c_str());
        return;
      }
      recorder = std::move(*opened);
      options.traceSinks.push_back(recorder.get());
    }
    sim::Simulation simulation(*cell, options);
    simulation.plc().machine().countInstructions(true);
    state.ResumeTiming();
    RunEnd end = simulation.run();  // with a recorder, its end() waits for the last commit
    state.PauseTiming();
    if (end != RunEnd::Completed) state.SkipWithError("the gearbox cycle did not complete");
    simulatedS = static_cast<double>(simulation.trace().cycleEndNs) * 1e-9;
    vmInstructions += static_cast<double>(simulation.plc().machine().instructionsExecuted());
    state.ResumeTiming();
  }
  for (const char* suffix : {"", "-wal", "-shm"})
    if (!historyPath.empty()) std::filesystem::remove(historyPath + suffix);
  state.counters["simulated_s"] = simulatedS;
  state.counters["vm_instr"] = benchmark::Counter(vmInstructions, benchmark::Counter::kAvgIterations);
  state.counters["realtime_factor"] =
      benchmark::Counter(simulatedS * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_GearboxCycle1ms(benchmark::State& state) { runGearbox(state, 1'000'000, true); }
void BM_GearboxCycle1msNoSkip(benchmark::State& state) { runGearbox(state, 1'000'000, false); }
void BM_GearboxCycle1msTick(benchmark::State& state) { runGearbox(state, 1'000'000, true, {}, false); }
void BM_GearboxCycle10ms(benchmark::State& state) { runGearbox(state, 10'000'000, true); }
void BM_GearboxCycle1msHistory(benchmark::State& state) {
  runGearbox(state, 1'000'000, true, (std::filesystem::temp_directory_path() / "virtcom_bench_gearbox.sqlite").string());
}

BENCHMARK(BM_GearboxCycle1ms)->Name("gearbox/cycle_1ms")->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_GearboxCycle1msNoSkip)->Name("gearbox/cycle_1ms_no_skip")->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_GearboxCycle1msTick)->Name("gearbox/cycle_1ms_tick")->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_GearboxCycle10ms)->Name("gearbox/cycle_10ms")->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_GearboxCycle1msHistory)->Name("gearbox/cycle_1ms_history")->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
}  // namespace virtcom::bench
