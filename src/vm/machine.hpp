#pragma once
// The bytecode interpreter: one memory image, a register stack and a call stack, all
// allocated once by the constructor. Modules must have passed bc::verifyModule.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/source.hpp"
#include "vm/compiled.hpp"
#include "vm/quicken.hpp"

namespace virtcom::vm {

struct FaultInfo {
  bc::FaultKind kind = bc::FaultKind::None;
  uint32_t pc = 0;                  // pc of the faulting instruction
  SourceLocation loc;               // module.locationOf(pc)
  std::vector<uint32_t> callStack;  // pcs of the call sites, innermost first (preallocated)
  // "division by zero at MAIN.st:12:5\n  called from FB_x.st:3:1 (in MAIN)"; allocates.
  std::string describe(const bc::Module& m) const;
};

class Machine {
 public:
  // Keeps a reference to `m` (which must outlive the machine) and allocates memory
  // (m.memorySize()), the register stack and the call stack. Memory starts zeroed: call
  // coldStart() before running.
  explicit Machine(const bc::Module& m);

  // memory[0, staticSize) = initialImage, the rest zero, sp = staticSize; then runs m.initPou
  // if set. Returns false if the init POU faulted (fault() says why).
  bool coldStart();
  // Runs m.exitPou if set (the FB_exit calls at the end of the program). Returns false if it
  // faulted (fault() says why).
  bool runExit() { return m_.exitPou == bc::Module::kNoPou || run(m_.exitPou, 0); }

  uint8_t* memory() { return memory_.data(); }
  const uint8_t* memory() const { return memory_.data(); }
  uint32_t memorySize() const { return static_cast<uint32_t>(memory_.size()); }

  void setTaskTimeNs(int64_t ns) { taskTimeNs_ = ns; }      // what SYSTIME returns
  void setBudget(uint64_t budget) { budget_ = budget; }     // backward jumps + calls per run()
  uint64_t budget() const { return budget_; }

  // Runs POU `pou` (an index into m.pous) with a fresh frame from its template at sp,
  // r0 = fp and r1 = thisAddress, until its RET. Returns true on normal completion; false on a
  // fault (fault() describes it; memory is left as is, sp is reset). An invalid pou index is
  // reported as an InvalidPointer fault at pc 0. The budget (watchdog) restarts on every run.
  // Never allocates, never throws, never touches memory outside the image.
  bool run(uint32_t pou, uint32_t thisAddress);

  // Runs every POU with `code` (machine code generated from this module by src/aot/) instead
  // of the interpreter from now on; null switches back. Results, faults and memory are the
  // same either way, except that instructionsExecuted() does not count compiled code.
  void useCompiled(std::shared_ptr<const CompiledCode> code) { compiled_ = std::move(code); }
  bool usesCompiled() const { return compiled_ != nullptr; }

  const FaultInfo& fault() const { return fault_; }
  // Interpreted instructions, cumulative since construction, counted only while
  // countInstructions(true) (benchmarks): the count costs an instruction per instruction.
  uint64_t instructionsExecuted() const { return executed_; }
  void countInstructions(bool on) { countInstructions_ = on; }
  // How often SYSTIME ran (cumulative): a scan that read no time and changed no memory is
  // idempotent, which lets the runtime skip identical scans exactly.
  uint64_t timeReads() const { return timeReads_; }
  // Current stack pointer (staticSize when idle).
  uint32_t stackPointer() const { return sp_; }

 private:
  struct CallFrame {
    const bc::Instr* returnIp;  // in `code`
    uint32_t base;              // caller's register window base
    uint64_t fp;                // callee frame base (restores sp on RET)
    const bc::Instr* code;      // the copy of the code the caller runs (quick_.code or the module's)
  };

  bool execute(uint32_t pou, uint32_t startSp);
  template <bool kCounting>
  bool interpret(uint32_t pou, uint32_t startSp);
  bool executeCompiled(uint32_t pou, uint32_t startSp);
  bool raise(bc::FaultKind kind, uint32_t pc, uint32_t depth, uint32_t startSp);

  const bc::Module& m_;
  std::vector<uint8_t> memory_;
  std::vector<uint8_t> scratch_;
  std::vector<uint64_t> regs_;
  std::vector<CallFrame> frames_;
  std::vector<uint32_t> compiledCallStack_;  // AotContext::callStack
  std::shared_ptr<const CompiledCode> compiled_;
  QuickCode quick_;  // after memory_: quickened for its size
  FaultInfo fault_;
  uint32_t sp_ = 0;
  int64_t taskTimeNs_ = 0;
  uint64_t budget_ = 50'000'000;
  uint64_t executed_ = 0;
  bool countInstructions_ = false;
  uint64_t timeReads_ = 0;
};

}  // namespace virtcom::vm
