#pragma once
// Opcodes and the 8-byte instruction word; the layout is drawn in opcodes.def.
#include <cstdint>
#include <span>
#include <string_view>

namespace virtcom::bc {

enum class Op : uint8_t {
#define X(name, fmt, meaning) name,
#include "bytecode/opcodes.def"
#undef X
  Count_
};

enum class Format : uint8_t { ABC, ABx, AsBx };

struct Instr {
  Op op = Op::NOP;
  uint8_t reserved = 0;
  uint16_t a = 0;
  uint16_t b = 0;
  uint16_t c = 0;

  uint32_t bx() const { return static_cast<uint32_t>(b) | (static_cast<uint32_t>(c) << 16); }
  int32_t sbx() const { return static_cast<int32_t>(bx()); }
  static Instr abc(Op op, uint16_t a, uint16_t b, uint16_t c) { return Instr{op, 0, a, b, c}; }
  static Instr abx(Op op, uint16_t a, uint32_t bx) {
    return Instr{op, 0, a, static_cast<uint16_t>(bx & 0xffff), static_cast<uint16_t>(bx >> 16)};
  }
  static Instr asbx(Op op, uint16_t a, int32_t sbx) { return abx(op, a, static_cast<uint32_t>(sbx)); }
};
static_assert(sizeof(Instr) == 8);

// Branches: JMP, JZ, JNZ and the fused compare-and-branch family (JEQ .. JGEK).
bool isBranch(Op op);
// The jump offset of a branch `ins`, relative to the next instruction (0 for other opcodes).
int32_t branchOffset(const Instr& ins);
inline int64_t branchTarget(uint32_t pc, const Instr& ins) { return int64_t{pc} + 1 + branchOffset(ins); }
// A copy of branch `ins` that jumps by `offset` instead (the caller checks that it fits: a
// signed 32-bit for JMP/JZ/JNZ, a signed 16-bit for the fused forms).
Instr withBranchOffset(const Instr& ins, int32_t offset);
// The largest offset magnitude `op`'s encoding holds (0 for non-branches).
int32_t maxBranchOffset(Op op);

enum class Native : uint16_t {
#define X(name, arity, meaning) name,
#include "bytecode/natives.def"
#undef X
  Count_
};

// The standard FBs with a native implementation (CALLFB), in native_fbs.def order.
enum class NativeFb : uint16_t {
#define FB(name) name,
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB
  Count_
};

// One instance member a native FB reads or writes.
struct NativeFbMember {
  std::string_view name;  // upper case, as in native_fbs.def
  uint32_t offset;
  uint32_t size;
};

std::string_view opName(Op op);
Format opFormat(Op op);
std::string_view nativeName(Native n);
unsigned nativeArity(Native n);
std::string_view nativeFbName(NativeFb f);
// The members of `f` with their offsets and sizes (empty for an invalid f).
std::span<const NativeFbMember> nativeFbMembers(NativeFb f);

// Run-time fault kinds (TRAP's Bx, and what the VM reports).
enum class FaultKind : uint8_t {
  None,
  DivisionByZero,
  IndexOutOfRange,
  InvalidPointer,
  StackOverflow,
  WatchdogBudget,
  InvalidEnumValue,
  AbstractCall,
  SubrangeViolation,
};
std::string_view faultText(FaultKind k);

}  // namespace virtcom::bc
