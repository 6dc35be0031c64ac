#pragma once
// Native (C++) functions reached by CALLN, one per line of bytecode/natives.def.
#include <algorithm>
#include <array>
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

// A standard FB run natively (CALLFB, bytecode/native_fbs.def) on the instance at `instance`,
// whose nativeFbSize bytes the caller has bounds-checked. Does exactly what the FB's ST body in
// lang/st/prelude.cpp does, statement for statement. Returns true if it read the task time
// `nowNs` (as the ST body's __SYSTIME_NS() would). Never allocates, never faults.
using NativeFbFn = bool (*)(uint8_t* instance, int64_t nowNs);

#define FB(name) bool nativeFb_##name(uint8_t* instance, int64_t nowNs);
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB

// The table indexed by bc::NativeFb.
inline constexpr NativeFbFn kNativeFbs[] = {
#define FB(name) &nativeFb_##name,
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB
};
static_assert(std::size(kNativeFbs) == static_cast<size_t>(bc::NativeFb::Count_));

// Bytes of instance memory each native FB touches (the end of its last member), for the
// bounds check before the call.
inline constexpr auto kNativeFbSizes = [] {
  std::array<uint32_t, static_cast<size_t>(bc::NativeFb::Count_)> size{};
  size_t fb = 0;
#define FB(name) fb = static_cast<size_t>(bc::NativeFb::name);
#define M(f, member, offset, ctype) size[fb] = std::max<uint32_t>(size[fb], offset + sizeof(ctype));
#include "bytecode/native_fbs.def"
#undef M
#undef FB
  return size;
}();

}  // namespace virtcom::vm
