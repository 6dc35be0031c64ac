// Wires and stop conditions on the PLC memory image.
#include <algorithm>
#include <string_view>

#include "cell/cell.hpp"
#include "core/ascii.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "core/value_codec.hpp"

namespace virtcom::cell {

Wire makeWire(TagId tag, plant::PortDir dir, const bc::VarRef& ref, ElemType varType, std::string varName) {
  Wire w;
  w.tag = tag;
  w.dir = dir;
  w.address = ref.address;
  w.bit = ref.bit;
  w.varType = varType;
  w.varName = std::move(varName);
  return w;
}

bool evaluate(const Condition& c, const uint8_t* memory) {
  if (!c.valid) return false;
  const uint8_t* p = memory + c.address;
  double v = c.bit >= 0 ? ((*p >> c.bit) & 1) : isRealType(c.type) ? loadReal(p, c.type) : static_cast<double>(loadInteger(p, c.type));
  switch (c.op) {
    case Condition::Op::Eq: return v == c.value;
    case Condition::Op::Ne: return v != c.value;
    case Condition::Op::Lt: return v < c.value;
    case Condition::Op::Le: return v <= c.value;
    case Condition::Op::Gt: return v > c.value;
    case Condition::Op::Ge: return v >= c.value;
  }
  return false;
}

namespace {

std::string_view trimSpaces(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

// The characters of a variable path (MAIN.Robot1.busy, MAIN.parts[2], %MW4); inside brackets
// anything goes, so an index expression is left to the variable resolver.
size_t variableLength(std::string_view text) {
  size_t i = 0;
  for (int depth = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '[') ++depth;
    else if (ch == ']') --depth;
    else if (depth == 0 && !isAsciiLetter(ch) && !isAsciiDigit(ch) && ch != '_' && ch != '.' && ch != '%') break;
  }
  return i;
}

struct ComparisonOperator {
  std::string_view symbol;
  Condition::Op op;
};
constexpr ComparisonOperator kOperators[] = {{"=", Condition::Op::Eq},  {"<>", Condition::Op::Ne}, {"<", Condition::Op::Lt},
                                             {"<=", Condition::Op::Le}, {">", Condition::Op::Gt},  {">=", Condition::Op::Ge},
                                             {"==", Condition::Op::Eq}, {"!=", Condition::Op::Ne}};

}  // namespace

// `VARIABLE OP VALUE`, or a BOOL `VARIABLE` alone (= TRUE). The text is split at the end of the
// variable's path, so a mistyped operator is named as such instead of becoming part of the name.
Condition parseCondition(const bc::Module& m, const std::string& text, SourceLocation loc, Diagnostics& diags) {
  Condition c;
  c.text = text;
  const std::string_view whole = trimSpaces(text);
  const size_t nameLength = variableLength(whole);
  const std::string name(whole.substr(0, nameLength));
  const std::string_view rest = trimSpaces(whole.substr(nameLength));
  std::string value = "TRUE";
  if (!rest.empty()) {
    // The operator: a run of comparison characters and spaces (so `> =` is caught whole), else
    // the next word (`gt`, `≥`).
    size_t opLength = std::min(rest.find_first_not_of("<>=! "), rest.size());
    if (opLength == 0) opLength = std::min(rest.find(' '), rest.size());
    const std::string_view symbol = trimSpaces(rest.substr(0, opLength));
    const auto* found = std::find_if(std::begin(kOperators), std::end(kOperators),
                                     [&](const ComparisonOperator& o) { return o.symbol == symbol; });
    if (found == std::end(kOperators)) {
      diags.error(celldiag::C020, loc, "condition '" + text + "': '" + std::string(symbol) +
                                           "' is not a comparison operator (expected one of: =, <>, <, <=, >, >=; "
                                           "== and != are accepted too)");
      return c;
    }
    c.op = found->op;
    value = trimSpaces(rest.substr(opLength));
  }
  auto ref = bc::resolveVariable(m, name);
  if (!ref) {
    diags.error(celldiag::C020, loc, "condition '" + text + "': the PLC has no variable '" + name + "'");
    return c;
  }
  const bc::TypeDesc& t = m.types[ref->type];
  if (t.kind != bc::TypeKind::Elementary && t.kind != bc::TypeKind::Enum) {
    diags.error(celldiag::C020, loc, "condition '" + text + "': '" + name + "' is not an elementary variable");
    return c;
  }
  // Parse the value with the module's own literal parser into a scratch copy of the variable.
  std::vector<uint8_t> scratch(m.memorySize(), 0);
  std::string problem = bc::writeValueFromText(m, *ref, value, scratch.data());
  if (!problem.empty()) {
    diags.error(celldiag::C020, loc, "condition '" + text + "': " + problem);
    return c;
  }
  c.address = ref->address;
  c.bit = ref->bit;
  c.type = t.elem;
  c.value = c.bit >= 0 ? ((scratch[c.address] >> c.bit) & 1)
            : isRealType(c.type) ? loadReal(scratch.data() + c.address, c.type)
                             : static_cast<double>(loadInteger(scratch.data() + c.address, c.type));
  c.valid = true;
  return c;
}

}  // namespace virtcom::cell
