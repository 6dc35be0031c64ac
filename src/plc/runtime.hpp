#pragma once
// The PLC runtime: cyclic tasks over one program image, with process images, RUN/STOP/FAULT
// and per-task statistics, on an injected clock (virtual or paced to the wall clock).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "vm/compiled_handoff.hpp"
#include "vm/machine.hpp"

namespace virtcom::plc {

enum class PlcState { Stop, Run, Fault };
const char* stateName(PlcState s);

struct TaskStats {
  uint64_t scans = 0;          // including skipped repeats
  uint64_t skippedScans = 0;
  int64_t minExecNs = 0;  // wall time of one scan's execution (statistics only)
  int64_t maxExecNs = 0;
  int64_t totalExecNs = 0;
  int64_t avgExecNs() const { return scans ? totalExecNs / static_cast<int64_t>(scans) : 0; }
};

struct RuntimeOptions {
  uint64_t instructionBudget = 50'000'000;  // per task scan: backward jumps + calls (watchdog)
  // Skip a scan when it would provably repeat the previous one: that scan read no time, changed
  // no memory, and neither the input image nor any variable (see inputsTouched) changed since.
  // Results are identical; only the executed-scan statistics differ. Single-task programs only.
  bool skipRepeatedScans = false;
};

// Which backend executed the scans (skipped repeats are not counted) and when it switched.
struct TierStats {
  uint64_t interpScans = 0;
  uint64_t compiledScans = 0;
  int64_t switchedAtNs = -1;  // virtual time of the first scan on machine code; -1: no switch
};

class Runtime {
 public:
  // `module` and `clock` must outlive the runtime.
  Runtime(const bc::Module& module, Clock& clock, RuntimeOptions options = {});

  // Loads initial values (cold start) and enters RUN. False if the init code faulted.
  bool coldStart();
  // Enters RUN from STOP; cold-starts first if the image was never loaded.
  void start() {
    if (!initialised_) coldStart();
    else if (state_ == PlcState::Stop) state_ = PlcState::Run;
  }
  void stop() { if (state_ == PlcState::Run) state_ = PlcState::Stop; }
  // Ends the program (CODESYS: before a new download or a reset): calls FB_exit of every
  // instance that has one and enters STOP; the next start() cold-starts. Nothing is called
  // after a fault or before the first cold start. False if FB_exit faulted (FAULT, faultText()).
  bool exit();
  PlcState state() const { return state_; }

  // The greatest common divisor of all task intervals: the scheduler's tick.
  int64_t baseTickNs() const { return baseTickNs_; }
  // Advances the clock to the next tick and runs every task due then (by priority, then in
  // declaration order): inputs -> PII, programs, PIQ -> outputs. Returns false once faulted or
  // stopped (the clock still advances while stopped). Allocates nothing on the normal path.
  bool tick();
  // Virtual time of the next tick to run, in ns.
  int64_t nextTickNs() const { return static_cast<int64_t>(tickIndex_) * baseTickNs_; }
  uint64_t ticks() const { return tickIndex_; }

  // Tells the runtime that something outside the PLC wrote its memory (wired variables,
  // protocol writes), so the next scan must run.
  void inputsTouched() { quiescent_ = false; }
  // True if the next scan would be skipped as a repeat (skipRepeatedScans) unless something
  // writes the PLC's memory or input image before it.
  bool scanWouldRepeat() const {
    return state_ == PlcState::Run && !shadow_.empty() && quiescent_ && inputImageSettled();
  }
  // Passes `count` ticks as tick() would if every scan in them repeated (scanWouldRepeat(), with
  // nothing written in between): the same tick count and statistics, nothing run.
  void skipRepeatedTicks(uint64_t count) {
    tickIndex_ += count;
    stats_[0].scans += count;
    stats_[0].skippedScans += count;
  }

  // The external side of the process image: written by devices/protocols, copied into the
  // %I area at the start of each scan; the %Q area is copied out at its end.
  uint8_t* inputImage() { return inputs_.data(); }
  const uint8_t* outputImage() const { return outputs_.data(); }

  // Tiered execution: once `handoff` is published, the runtime runs on its machine code from the
  // start of the next executed scan on (never inside a scan). Memory, time and the repeated-scan
  // state carry over unchanged: both backends give the same results. Set before the run.
  void switchToCompiledWhenReady(std::shared_ptr<const vm::CompiledHandoff> handoff) { tierUp_ = std::move(handoff); }
  const TierStats& tierStats() const { return tier_; }

  const bc::Module& module() const { return module_; }
  vm::Machine& machine() { return machine_; }
  const vm::Machine& machine() const { return machine_; }
  const TaskStats& stats(size_t task) const { return stats_[task]; }
  // The fault report with source location and call stack, empty if not faulted.
  std::string faultText() const;

 private:
  bool runTask(size_t task, int64_t nowNs);
  bool inputImageSettled() const;
  void switchToCompiled(int64_t nowNs);

  const bc::Module& module_;
  Clock& clock_;
  RuntimeOptions options_;
  vm::Machine machine_;
  PlcState state_ = PlcState::Stop;
  bool initialised_ = false;
  int64_t baseTickNs_ = 10'000'000;
  uint64_t tickIndex_ = 0;
  std::vector<size_t> taskOrder_;  // by priority
  std::vector<uint8_t> inputs_;
  std::vector<uint8_t> outputs_;
  std::vector<TaskStats> stats_;
  std::string faultTask_;
  bool quiescent_ = false;          // the last executed scan was a provable no-op
  std::vector<uint8_t> shadow_;     // static memory before the last executed scan
  std::shared_ptr<const vm::CompiledHandoff> tierUp_;  // null once switched (or never tiering)
  TierStats tier_;
};

}  // namespace virtcom::plc
