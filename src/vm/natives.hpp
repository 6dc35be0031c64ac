#pragma once
// Native (C++) functions reached by CALLN, one per line of bytecode/natives.def.
#include <cstdint>

#include "bytecode/instruction.hpp"

namespace virtcom::vm {

// What a native may touch: the memory image and a scratch buffer of at least memorySize bytes
// (used to build string results so that a destination may alias a source).
struct NativeContext {
  uint8_t* memory = nullptr;
  uint32_t memorySize = 0;
  uint32_t nullGuard = 16;
  uint8_t* scratch = nullptr;
};

// A native reads its arguments from args[0..arity) and writes its result to args[0].
// Returns FaultKind::None, or the fault to raise (InvalidPointer for a bad string address).
// Never allocates, never throws.
using NativeFn = bc::FaultKind (*)(uint64_t* args, const NativeContext& ctx);

#define X(name, arity, meaning) bc::FaultKind native_##name(uint64_t* args, const NativeContext& ctx);
#include "bytecode/natives.def"
#undef X

// The native table indexed by bc::Native.
inline constexpr NativeFn kNatives[] = {
#define X(name, arity, meaning) &native_##name,
#include "bytecode/natives.def"
#undef X
};
static_assert(std::size(kNatives) == static_cast<size_t>(bc::Native::Count_));

}  // namespace virtcom::vm
