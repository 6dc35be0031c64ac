// Benchmark (5): one scan of a cell controller for 8 devices (bench/st/cell.st), with its
// C++ twin for reference and a variant that calls the VM without the runtime around it.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>

#include "native_fbs.hpp"
#include "st_program.hpp"

namespace virtcom::bench {
namespace {

constexpr int64_t kScanNs = 10'000'000;
constexpr int kVerifyScans = 1000;  // 10 s of cell time: many cycles, faults and acknowledgements

enum class Step : uint8_t { Idle, Start, WaitDone, Release, Fault };
enum class CellState : uint8_t { Init, Running, Acknowledge };

// FB_Device from cell.st.
struct NativeDevice {
  bool execute = false;
  int16_t delayScans = 0;
  bool done = false;
  bool busy = false;
  int16_t count = 0;

  void call() {
    if (!execute) {
      done = false;
      busy = false;
      count = 0;
    } else if (!done) {
      busy = true;
      count = static_cast<int16_t>(count + 1);
      if (count >= delayScans) {
        done = true;
        busy = false;
      }
    }
  }
};

// FB_Station from cell.st.
struct NativeStation {
  bool enable = false;
  bool ackFault = false;
  bool done = false;
  int32_t timeoutMs = 0;
  bool execute = false;
  bool faulted = false;
  int32_t cycles = 0;
  int32_t faults = 0;
  Step step = Step::Idle;
  NativeRTrig doneEdge;
  NativeTon watchdog;

  void call(int64_t nowNs) {
    doneEdge.clk = done;
    doneEdge.call();
    watchdog.in = step == Step::WaitDone;
    watchdog.ptMs = timeoutMs;
    watchdog.call(nowNs);
    switch (step) {
      case Step::Idle:
        if (enable) step = Step::Start;
        break;
      case Step::Start:
        execute = true;
        step = Step::WaitDone;
        break;
      case Step::WaitDone:
        if (doneEdge.q) {
          execute = false;
          cycles = cycles + 1;
          step = Step::Release;
        } else if (watchdog.q) {
          execute = false;
          faults = faults + 1;
          step = Step::Fault;
        }
        break;
      case Step::Release:
        if (!done) step = Step::Idle;
        break;
      case Step::Fault:
        if (ackFault) step = Step::Idle;
        break;
    }
    faulted = step == Step::Fault;
  }
};

// The PROGRAM instance of cell.st (index d - 1 is the ST index d).
struct CellProgram {
  CellState cell = CellState::Init;
  std::array<NativeStation, 8> stations;
  std::array<NativeDevice, 8> devices;
  NativeTon ackTimer;
  bool ack = false;
  bool anyFault = false;
  int32_t totalCycles = 0;
  int32_t totalFaults = 0;
  int32_t acks = 0;
};

[[gnu::noinline]] void cellScan(CellProgram& p, int64_t nowNs) {
  p.anyFault = false;
  p.totalCycles = 0;
  p.totalFaults = 0;
  for (int d = 1; d <= 8; ++d) {
    NativeDevice& dev = p.devices[d - 1];
    NativeStation& st = p.stations[d - 1];
    dev.execute = st.execute;
    dev.delayScans = static_cast<int16_t>(d == 8 ? 25 : 2 + d % 3);
    dev.call();
    st.enable = p.cell == CellState::Running;
    st.ackFault = p.ack;
    st.done = dev.done;
    st.timeoutMs = 200;
    st.call(nowNs);
    p.anyFault = p.anyFault || st.faulted;
    p.totalCycles = p.totalCycles + st.cycles;
    p.totalFaults = p.totalFaults + st.faults;
  }
  p.ackTimer.in = p.anyFault && p.cell == CellState::Running;
  p.ackTimer.ptMs = 100;
  p.ackTimer.call(nowNs);
  p.ack = false;
  switch (p.cell) {
    case CellState::Init:
      p.cell = CellState::Running;
      break;
    case CellState::Running:
      if (p.ackTimer.q) p.cell = CellState::Acknowledge;
      break;
    case CellState::Acknowledge:
      p.ack = true;
      p.acks = p.acks + 1;
      p.cell = CellState::Running;
      break;
  }
}

// Runs the ST program and the twin for kVerifyScans scans and compares what they counted.
bool verifyCell(benchmark::State& state, StProgram& prog) {
  if (!warmUp(state, prog, kVerifyScans)) return false;
  CellProgram twin;
  for (int k = 0; k < kVerifyScans; ++k) cellScan(twin, k * kScanNs);
  if (twin.totalCycles == 0 || twin.totalFaults == 0 || twin.acks == 0) {
    state.SkipWithError("the cell twin never completed a cycle, fault and acknowledgement");
    return false;
  }
  return expectValue(state, prog, "MAIN.totalCycles", twin.totalCycles) &&
         expectValue(state, prog, "MAIN.totalFaults", twin.totalFaults) &&
         expectValue(state, prog, "MAIN.acks", twin.acks) &&
         expectValue(state, prog, "MAIN.stations[1].cycles", twin.stations[0].cycles) &&
         expectValue(state, prog, "MAIN.stations[8].faults", twin.stations[7].faults);
}

void cellVm(benchmark::State& state, Backend backend) {
  StProgram prog("cell.st", backend);
  if (!verifyCell(state, prog)) return;
  measureScans(state, prog);
}

void cellVmMachineRun(benchmark::State& state, Backend backend) {
  StProgram prog("cell.st", backend);
  if (!verifyCell(state, prog)) return;
  measureMachineRuns(state, prog);
}

void cellNative(benchmark::State& state) {
  CellProgram p;
  int64_t nowNs = 0;
  for (auto _ : state) {
    cellScan(p, nowNs);
    benchmark::ClobberMemory();
    nowNs += kScanNs;
  }
  benchmark::DoNotOptimize(p.totalCycles);
  reportNative(state);
}

BENCHMARK_CAPTURE(cellVm, interp, Backend::Interp)->Name("cell/vm")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(cellVm, aot, Backend::Aot)->Name("cell/aot")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(cellVmMachineRun, interp, Backend::Interp)->Name("cell/vm_machine_run")->Apply(withMinStatistic);
BENCHMARK_CAPTURE(cellVmMachineRun, aot, Backend::Aot)->Name("cell/aot_machine_run")->Apply(withMinStatistic);
BENCHMARK(cellNative)->Name("cell/native")->Apply(withMinStatistic);

}  // namespace
}  // namespace virtcom::bench
