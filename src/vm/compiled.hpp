#pragma once
// The interface between the VM and machine code generated from a module's bytecode (src/aot/).
// A compiled module is one C function per POU. It works on the interpreter's own memory image
// and register stack and reports faults the interpreter's way, so Machine::run can call it in
// place of the dispatch loop and nothing else can tell the difference.
#include <cstdint>
#include <memory>
#include <vector>

namespace virtcom::vm {

// The state a compiled POU function shares with the machine. The generated C source declares
// the same struct from this very macro's text (aot::kAbiText), so the two cannot diverge.
// `natives` points at kNatives, `nctx` at a NativeContext. Native FBs need no pointer: the
// generated code carries their C source (vm/native_fbs_c.def).
#define VIRTCOM_AOT_ABI                                                            \
  struct AotContext {                                                              \
    uint8_t* mem;                                                                  \
    const uint8_t* image;                                                          \
    uint64_t* regs;                                                                \
    uint32_t* callStack;                                                           \
    const void* natives;                                                           \
    const void* nctx;                                                              \
    uint64_t regCount;                                                             \
    uint64_t sp;                                                                   \
    uint64_t remaining;                                                            \
    int64_t taskTimeNs;                                                            \
    uint64_t timeReads;                                                            \
    uint32_t maxDepth;                                                             \
    uint32_t faultPc;                                                              \
    uint32_t callStackSize;                                                        \
  };                                                                               \
  typedef int (*AotEntry)(struct AotContext* c, uint32_t base, uint32_t depth);
VIRTCOM_AOT_ABI

// Bumped whenever the meaning of AotContext or of an entry's result changes.
inline constexpr uint32_t kAotAbiVersion = 2;

// One entry per POU, indexed like Module::pous. An entry runs the POU with its register window
// at regs + base (r0 = fp, r1 = this already set) at call depth `depth` and returns 0 after its
// RET, or a bc::FaultKind with c->faultPc set and c->callStack[0, callStackSize) holding the
// pcs of the call sites, innermost first.
struct CompiledCode {
  std::vector<AotEntry> entries;
  std::shared_ptr<void> library;  // keeps the shared object loaded
};

}  // namespace virtcom::vm
