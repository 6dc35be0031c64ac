// Wires and stop conditions on the PLC memory image.
#include <cstring>

#include "cell/cell.hpp"
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

Condition parseCondition(const bc::Module& m, const std::string& text, SourceLocation loc, Diagnostics& diags) {
  Condition c;
  c.text = text;
  static const std::pair<const char*, Condition::Op> kOps[] = {{">=", Condition::Op::Ge}, {"<=", Condition::Op::Le},
                                                               {"<>", Condition::Op::Ne}, {"!=", Condition::Op::Ne},
                                                               {"==", Condition::Op::Eq}, {"=", Condition::Op::Eq},
                                                               {">", Condition::Op::Gt},  {"<", Condition::Op::Lt}};
  size_t pos = std::string::npos, len = 0;
  for (const auto& [sym, op] : kOps) {
    size_t p = text.find(sym);
    if (p != std::string::npos) {
      pos = p;
      len = std::strlen(sym);
      c.op = op;
      break;
    }
  }
  auto trim = [](std::string s) {
    while (!s.empty() && s.back() == ' ') s.pop_back();
    while (!s.empty() && s.front() == ' ') s.erase(s.begin());
    return s;
  };
  std::string name = trim(pos == std::string::npos ? text : text.substr(0, pos));
  std::string value = pos == std::string::npos ? "TRUE" : trim(text.substr(pos + len));
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
