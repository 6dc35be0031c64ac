#pragma once
// One benchmark program: a bench/st/*.st file compiled once and run on the soft PLC in
// virtual time, plus typed access to its variables so a benchmark can check its result
// against the C++ twin before measuring.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "plc/runtime.hpp"

namespace virtcom::bench {

// How the PLC runs the program: the bytecode interpreter (`<case>/vm`) or machine code from
// the AOT backend, src/aot (`<case>/aot`).
enum class Backend { Interp, Aot };

class StProgram {
 public:
  // Reads `fileName` from the bench ST directory (VIRTCOM_BENCH_DIR), compiles it (for
  // Backend::Aot also to machine code) and cold starts a runtime on a virtual clock. On any
  // failure ok() is false and error() says why (rendered diagnostics, the C compiler's
  // complaint or the fault text). Allocates; never throws on bad input.
  // `coverage`: compiled with coverage probes (docs/coverage.md), to measure what they cost.
  explicit StProgram(std::string_view fileName, Backend backend = Backend::Interp, bool coverage = false);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  // One scan of the default task (Runtime::tick: the clock advances by the task interval).
  // False on a runtime fault; error() then holds the fault text.
  bool scan();
  // Runs the program `MAIN` once through vm::Machine::run with the task time set to `nowNs`
  // (no process-image copies, no statistics): the bare interpreter (or AOT code) cost of one scan.
  bool runMain(int64_t nowNs);

  plc::Runtime& runtime() { return *runtime_; }
  const bc::Module& module() const { return *module_; }
  uint64_t instructionsExecuted() const { return runtime_->machine().instructionsExecuted(); }

  // The value of the variable at `path` (e.g. "MAIN.acc") if it exists, is not a packed bit
  // and has exactly sizeof(T) bytes; nullopt otherwise. This and text() require ok() after
  // construction (a program that never compiled has no memory to read).
  template <class T>
  std::optional<T> read(std::string_view path) const {
    auto ref = bc::resolveVariable(*module_, path);
    if (!ref || ref->bit >= 0 || module_->types[ref->type].size != sizeof(T)) return std::nullopt;
    T value;
    std::memcpy(&value, runtime_->machine().memory() + ref->address, sizeof(T));
    return value;
  }
  // The IEC literal text of the variable at `path` (for messages), or "<unknown path>".
  std::string text(std::string_view path) const;

 private:
  std::string error_;
  std::unique_ptr<bc::Module> module_;
  VirtualClock clock_;
  std::unique_ptr<plc::Runtime> runtime_;
  uint32_t mainPou_ = 0;
  uint32_t mainAddress_ = 0;
};

// Runs `scans` scans before measuring (the result check reads what they computed). If the
// program failed to load or faults, marks `state` skipped with the reason and returns false.
bool warmUp(benchmark::State& state, StProgram& prog, int scans);

// Compares the ST variable at `path` with the C++ twin's `want` (exact equality, also for
// REAL: both sides round every operation to single precision). On a mismatch marks `state`
// skipped with both values and returns false.
template <class T>
bool expectValue(benchmark::State& state, const StProgram& prog, std::string_view path, const T& want) {
  const std::optional<T> got = prog.read<T>(path);
  if (got && std::memcmp(&*got, &want, sizeof(T)) == 0) return true;
  std::ostringstream msg;
  msg.precision(9);
  msg << "ST result differs from the C++ twin: " << path << " = " << prog.text(path);
  if constexpr (std::is_arithmetic_v<T>) msg << ", twin = " << +want;
  state.SkipWithError(msg.str().c_str());
  return false;
}

// Like expectValue for a STRING variable: compares its text with `want` (plain characters,
// no `$` escapes needed).
bool expectString(benchmark::State& state, const StProgram& prog, std::string_view path, std::string_view want);

// The measured loop of every VM benchmark: one PLC scan (Runtime::tick) per iteration.
// Reports scans per second as items/s and the VM instructions executed per scan.
void measureScans(benchmark::State& state, StProgram& prog);

// Like measureScans, but calls vm::Machine::run on MAIN directly (the time still advances
// by 10 ms per iteration): the scan without the runtime's bookkeeping.
void measureMachineRuns(benchmark::State& state, StProgram& prog);

// Registration option of every benchmark here: with --benchmark_repetitions=N, also report
// the minimum over the repetitions ("_min"), the robust statistic on a shared machine where
// other processes only ever add time.
void withMinStatistic(benchmark::internal::Benchmark* b);

// The counters of a native twin's benchmark: scans per second as items/s and vm_instr = 0,
// so the twins share one table with the VM benchmarks.
void reportNative(benchmark::State& state);

}  // namespace virtcom::bench
