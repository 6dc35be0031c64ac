#pragma once
// Which registers a generated POU function moves between its C locals and the register stack.
// The interpreter keeps every register in the register stack; the generated code keeps them in
// locals and touches the stack only where bytecode can tell the difference: at a CALL (the
// callee reads its window, the caller reads back what the callee left there) and on entry and
// return. A liveness pass over each POU, joined over the call graph, narrows these to the
// registers that are read afterwards.
#include <cstdint>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::aot {

// One flag per register slot, counted from a POU's window base. A set may reach beyond the
// window: register windows overlap, so a caller can read back what a callee's callee left
// above the callee's own window.
using RegisterSet = std::vector<bool>;

struct PouRegisters {
  RegisterSet loadOnEntry;  // registers the POU may read before writing them
  RegisterSet writeBack;    // registers of its window that callers read after it returns
  // Per instruction (pc - codeStart), only for CALL: the caller's registers read after the
  // call returns. Those at or above the call's A are stored before the call and reloaded.
  std::vector<RegisterSet> liveAfterCall;
};

struct RegisterPlan {
  // Per POU: the slots it, or a POU it calls, may read before writing them (typically r0 = fp
  // and r1 = this). A caller stores those of its registers before the call.
  std::vector<RegisterSet> inputs;
  std::vector<PouRegisters> pous;
};

// The plan for a module that passed bc::verifyModule. A least fixed point over the call
// graph, so recursion is covered. Faults are not exits that write back: after a fault no
// bytecode reads a register before writing it.
RegisterPlan planRegisters(const bc::Module& m);

}  // namespace virtcom::aot
