#include "bytecode/instruction.hpp"

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

static_assert(std::size(kOpNames) == static_cast<size_t>(Op::Count_));
static_assert(std::size(kNativeNames) == static_cast<size_t>(Native::Count_));

}  // namespace

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
