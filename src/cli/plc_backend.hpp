#pragma once
// `--backend`: how the soft PLC runs its program, for every command that runs one.
//   interp  the bytecode interpreter only;
//   aot     machine code compiled (or taken from the cache) before the first scan;
//   auto    (the default) machine code from the first scan when the AOT cache holds this
//           module's (a former aot run or a long auto run compiled it); else the interpreter at
//           once, and a run still going after half a second has its machine code compiled on a
//           background thread and switched to between two scans when it is ready
//           (plc::Runtime's tier switch). Without a C compiler it stays on the interpreter,
//           silently.
#include <memory>
#include <string>

#include "bytecode/module.hpp"
#include "plc/runtime.hpp"
#include "vm/compiled_handoff.hpp"

namespace virtcom::cli {

class PlcBackend {
 public:
  // Load time. `backend` is one of the --backend values. For aot a compile failure prints a
  // one-line notice on stderr and leaves the interpreter. For auto the compile runs on its own
  // thread over a copy of `m`, so `m` may go before this object does.
  // Test hook: with $VIRTCOM_TIER_SWITCH_AT_SCAN=K, auto compiles before returning and the
  // runtime switches before its scan K+1 (K scans interpreted), so a test places the switch.
  PlcBackend(const std::string& backend, const bc::Module& m);
  // Returns promptly even while the background compile still runs: its compiler processes
  // are terminated (the C compiler and aot::compileModule remove their temporary files) and
  // the thread is waited for at most a bound, then left to finish alone.
  ~PlcBackend();
  PlcBackend(const PlcBackend&) = delete;
  PlcBackend& operator=(const PlcBackend&) = delete;

  // Machine code to run from the first scan on (aot, or auto with a warm cache), else null.
  std::shared_ptr<const vm::CompiledCode> compiled() const { return compiled_; }
  // Machine code to switch to once published (auto), else null.
  std::shared_ptr<const vm::CompiledHandoff> tierUp() const { return handoff_; }
  // Hands both to a runtime (exec; the simulation does it from SimOptions).
  void attach(plc::Runtime& runtime) const;
  // With $VIRTCOM_TIER_LOG set: one line on stderr about the run's backends (measurements).
  void logRun(const plc::TierStats& stats) const;

 private:
  struct Compile;
  std::string requested_;
  std::shared_ptr<const vm::CompiledCode> compiled_;
  std::shared_ptr<vm::CompiledHandoff> handoff_;
  std::shared_ptr<Compile> compile_;  // auto: the background compile's state, shared with its thread
};

}  // namespace virtcom::cli
