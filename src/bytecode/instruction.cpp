#include "bytecode/instruction.hpp"

#include <array>
#include <cstdint>

namespace virtcom::bc {

namespace {

constexpr std::string_view kOpNames[] = {
#define X(name, fmt, meaning) #name,
#include "bytecode/opcodes.def"
#undef X
};

constexpr Format kOpFormats[] = {
#define X(name, fmt, meaning) Format::fmt,
#include "bytecode/opcodes.def"
#undef X
};

constexpr std::string_view kNativeNames[] = {
#define X(name, arity, meaning) #name,
#include "bytecode/natives.def"
#undef X
};

constexpr unsigned kNativeArity[] = {
#define X(name, arity, meaning) arity,
#include "bytecode/natives.def"
#undef X
};

constexpr std::string_view kNativeFbNames[] = {
#define FB(name) #name,
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB
};

// All members of all native FBs, grouped by FB in table order.
constexpr NativeFbMember kNativeFbMembers[] = {
#define FB(name)
#define M(fb, member, offset, ctype) {#member, offset, sizeof(ctype)},
#include "bytecode/native_fbs.def"
#undef M
#undef FB
};

// Index of each FB's first member in kNativeFbMembers, plus the end.
constexpr auto kNativeFbFirst = [] {
  std::array<uint32_t, static_cast<size_t>(NativeFb::Count_) + 1> first{};
  uint32_t fb = 0, members = 0;
#define FB(name) first[fb++] = members;
#define M(fb, member, offset, ctype) ++members;
#include "bytecode/native_fbs.def"
#undef M
#undef FB
  first[fb] = members;
  return first;
}();

static_assert(std::size(kOpNames) == static_cast<size_t>(Op::Count_));
static_assert(std::size(kNativeFbNames) == static_cast<size_t>(NativeFb::Count_));
static_assert(std::size(kNativeNames) == static_cast<size_t>(Native::Count_));

}  // namespace

namespace {
// The fused forms whose offset is in B (the constant is in C); the register forms keep it in C.
bool offsetInB(Op op) {
  return op == Op::JEQK || op == Op::JNEK || op == Op::JLTK || op == Op::JLEK || op == Op::JGTK || op == Op::JGEK;
}
bool fusedBranch(Op op) {
  return offsetInB(op) || op == Op::JEQ || op == Op::JNE || op == Op::JLT_I || op == Op::JLE_I || op == Op::JLT_U ||
         op == Op::JLE_U;
}
}  // namespace

bool isBranch(Op op) { return op == Op::JMP || op == Op::JZ || op == Op::JNZ || fusedBranch(op); }

int32_t branchOffset(const Instr& ins) {
  if (offsetInB(ins.op)) return static_cast<int16_t>(ins.b);
  if (fusedBranch(ins.op)) return static_cast<int16_t>(ins.c);
  return isBranch(ins.op) ? ins.sbx() : 0;
}

Instr withBranchOffset(const Instr& ins, int32_t offset) {
  Instr out = ins;
  if (offsetInB(ins.op)) out.b = static_cast<uint16_t>(offset);
  else if (fusedBranch(ins.op)) out.c = static_cast<uint16_t>(offset);
  else if (isBranch(ins.op)) out = Instr::asbx(ins.op, ins.a, offset);
  return out;
}

int32_t maxBranchOffset(Op op) { return fusedBranch(op) ? INT16_MAX : isBranch(op) ? INT32_MAX : 0; }

std::string_view opName(Op op) {
  auto i = static_cast<size_t>(op);
  return i < std::size(kOpNames) ? kOpNames[i] : std::string_view("?");
}

Format opFormat(Op op) {
  auto i = static_cast<size_t>(op);
  return i < std::size(kOpFormats) ? kOpFormats[i] : Format::ABC;
}

std::string_view nativeName(Native n) {
  auto i = static_cast<size_t>(n);
  return i < std::size(kNativeNames) ? kNativeNames[i] : std::string_view("?");
}

unsigned nativeArity(Native n) {
  auto i = static_cast<size_t>(n);
  return i < std::size(kNativeArity) ? kNativeArity[i] : 0;
}

std::string_view nativeFbName(NativeFb f) {
  auto i = static_cast<size_t>(f);
  return i < std::size(kNativeFbNames) ? kNativeFbNames[i] : std::string_view("?");
}

std::span<const NativeFbMember> nativeFbMembers(NativeFb f) {
  auto i = static_cast<size_t>(f);
  if (i >= std::size(kNativeFbNames)) return {};
  return std::span(kNativeFbMembers).subspan(kNativeFbFirst[i], kNativeFbFirst[i + 1] - kNativeFbFirst[i]);
}

// A switch without default: adding a FaultKind without a text is a -Wswitch warning.
std::string_view faultText(FaultKind k) {
  switch (k) {
    case FaultKind::None: return "no fault";
    case FaultKind::DivisionByZero: return "division by zero";
    case FaultKind::IndexOutOfRange: return "array index out of range";
    case FaultKind::InvalidPointer: return "invalid pointer access";
    case FaultKind::StackOverflow: return "stack overflow";
    case FaultKind::WatchdogBudget: return "watchdog: instruction budget exhausted";
    case FaultKind::InvalidEnumValue: return "invalid enum value";
    case FaultKind::AbstractCall: return "call of an abstract method";
    case FaultKind::SubrangeViolation: return "subrange violation";
  }
  return "unknown fault";
}

}  // namespace virtcom::bc
