// Code generation: the string standard functions (LEN, FIND, LEFT, RIGHT, MID, INSERT, DELETE,
// REPLACE, CONCAT) as CALLN of the STR_ natives, or their WSTR_ twins for WSTRING inputs.
#include "lang/st/codegen/builtin.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

// The string inputs of one call: the first decides STRING or WSTRING, the others must agree.
class StringInputs {
 public:
  explicit StringInputs(BuiltinCall& c) : c_(c) {}

  // Input i in a register (its address); nullopt after E202.
  std::optional<uint16_t> operator[](size_t i) {
    TypeTable& t = c_.types();
    Value v = c_.arg(i);
    if (!v.ok()) return std::nullopt;
    if (!isStringValue(t, v)) {
      c_.diags().error(diag::E202, c_.args[i]->loc, c_.name() + " needs a STRING here, found " + describe(t, v.type));
      return std::nullopt;
    }
    bool w = v.type != kNoType && t.isWideString(v.type);
    if (i == 0) {
      wide_ = w;
    } else if (w != wide_) {
      c_.diags().error(diag::E202, c_.args[i]->loc,
                       c_.name() + " cannot mix STRING and WSTRING; convert with STRING_TO_WSTRING");
      return std::nullopt;
    }
    return c_.pc.toReg(v);
  }

  bc::Native native() const { return wide_ ? wideNative(c_.fn.lowering.native) : c_.fn.lowering.native; }
  TypeId resultType() const { return c_.types().stringOf(kStringResultLength, wide_); }

 private:
  BuiltinCall& c_;
  bool wide_ = false;
};

// The native's arguments: the string inputs (all evaluated, so each one reports), then the
// integers: the IEC inputs L (a length) and P (a position), which always come last. Nullopt if
// a string input was wrong.
std::optional<std::vector<uint16_t>> operands(BuiltinCall& c, StringInputs& strings) {
  auto isInteger = [&](size_t i) {
    std::string_view name = listedParameter(c.fn.parameters, i);
    return name == "L" || name == "P";
  };
  std::vector<uint16_t> regs;
  bool ok = true;
  size_t i = 0;
  for (; i < c.count() && !isInteger(i); ++i) {
    auto s = strings[i];
    ok = ok && s.has_value();
    if (s) regs.push_back(*s);
  }
  if (!ok) return std::nullopt;
  for (; i < c.count(); ++i) regs.push_back(c.dint(c.arg(i)));
  return regs;
}

}  // namespace

Value emitStringQuery(BuiltinCall& c) {
  StringInputs strings(c);
  auto regs = operands(c, strings);
  if (!regs) return Value::error();
  Value lengthOrPosition = c.pc.callNative(strings.native(), *regs, TypeTable::elem(ElemType::Dint));
  return c.pc.convert(lengthOrPosition, TypeTable::elem(ElemType::Int), c.loc());
}

Value emitStringEdit(BuiltinCall& c) {
  StringInputs strings(c);
  auto regs = operands(c, strings);
  if (!regs) return Value::error();
  return c.pc.stringResult(strings.native(), *regs, strings.resultType());
}

// CONCAT(a, b, c) = CONCAT(CONCAT(a, b), c), each step into a fresh STRING(255).
Value emitStringConcat(BuiltinCall& c) {
  StringInputs strings(c);
  auto first = strings[0];
  if (!first) return Value::error();
  Value acc;
  uint16_t left = *first;
  for (size_t i = 1; i < c.count(); ++i) {
    auto right = strings[i];
    if (!right) return Value::error();
    acc = c.pc.stringResult(strings.native(), {left, *right}, strings.resultType());
    left = c.pc.addressOf(acc.place);
  }
  return acc;
}

}  // namespace virtcom::st
