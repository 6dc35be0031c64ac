#pragma once
// Opcodes and the 8-byte instruction word; the layout is drawn in opcodes.def.
#include <cstdint>
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

enum class Native : uint16_t {
#define X(name, arity, meaning) name,
#include "bytecode/natives.def"
#undef X
  Count_
};

std::string_view opName(Op op);
Format opFormat(Op op);
std::string_view nativeName(Native n);
unsigned nativeArity(Native n);

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
