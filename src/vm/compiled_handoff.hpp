#pragma once
// Tiered execution (`--backend auto`): machine code compiled on a background thread, handed to
// the scan thread, which switches to it between two scans (plc::Runtime::tick).
//
// Race freedom: the compiling thread writes code_ once and then sets ready_ with release
// order; the scan thread tests ready_ with one relaxed load per scan (no lock, no fence on the
// hot path) and only after seeing it set loads it again with acquire order before reading
// code_, so it reads the fully written pointer. code_ is never written again, so any number of runtimes
// (a run restarted from the HMI) may read it.
#include <atomic>
#include <cstdint>
#include <memory>

#include "vm/compiled.hpp"

namespace virtcom::vm {

class CompiledHandoff {
 public:
  // Any thread, at most once, with non-null code. Never blocks.
  void publish(std::shared_ptr<const CompiledCode> code) {
    code_ = std::move(code);
    ready_.store(true, std::memory_order_release);
  }
  // A test hook: the code is not taken before `scans` scans have run on the interpreter, so a
  // test can place the switch at a scan of its choice. Set before the run starts.
  void holdUntilScan(uint64_t scans) { holdUntilScan_ = scans; }

  // The scan thread, once per scan: true once the code is published and, after `scansRun`
  // interpreted scans, no longer held. Then code() may be called. Lock-free, allocation-free.
  bool readyAfter(uint64_t scansRun) const {
    return ready_.load(std::memory_order_relaxed) && scansRun >= holdUntilScan_;
  }
  bool published() const { return ready_.load(std::memory_order_acquire); }
  // The published code (null before publish()); after readyAfter() returned true on this
  // thread it is the code.
  std::shared_ptr<const CompiledCode> code() const {
    return ready_.load(std::memory_order_acquire) ? code_ : nullptr;
  }

 private:
  std::shared_ptr<const CompiledCode> code_;
  std::atomic<bool> ready_{false};
  uint64_t holdUntilScan_ = 0;
};

}  // namespace virtcom::vm
