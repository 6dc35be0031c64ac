// Typed value transfers between the PLC memory image and the tag bus, and stop conditions.
#include <cstring>

#include "cell/cell.hpp"

namespace virtcom::cell {

namespace {

// The variable's value as a double or an integer, by its storage type.
bool isReal(ElemType t) { return t == ElemType::Real || t == ElemType::Lreal; }

int64_t loadInt(const uint8_t* p, ElemType t) {
  switch (t) {
    case ElemType::Bool: case ElemType::Byte: case ElemType::Usint: return *p;
    case ElemType::Sint: return static_cast<int8_t>(*p);
    case ElemType::Int: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case ElemType::Word: case ElemType::Uint: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case ElemType::Dint: case ElemType::Time: { int32_t v; std::memcpy(&v, p, 4); return v; }
    case ElemType::Dword: case ElemType::Udint: case ElemType::Date: case ElemType::Tod: case ElemType::Dt: {
      uint32_t v; std::memcpy(&v, p, 4); return v;
    }
    default: { int64_t v; std::memcpy(&v, p, 8); return v; }
  }
}

double loadReal(const uint8_t* p, ElemType t) {
  if (t == ElemType::Real) { float f; std::memcpy(&f, p, 4); return f; }
  double d; std::memcpy(&d, p, 8); return d;
}

void storeInt(uint8_t* p, ElemType t, int64_t v) {
  if (t == ElemType::Bool) v = v != 0;
  std::memcpy(p, &v, elemTypeInfo(t).sizeBytes);  // little endian: the low bytes
}

void storeReal(uint8_t* p, ElemType t, double v) {
  if (t == ElemType::Real) { float f = static_cast<float>(v); std::memcpy(p, &f, 4); return; }
  std::memcpy(p, &v, 8);
}


void storeValue(const Wire& w, const TagBus& bus, uint8_t* p) {
  if (w.bit >= 0) {
    if (bus.getBool(w.tag)) *p = static_cast<uint8_t>(*p | (1u << w.bit));
    else *p = static_cast<uint8_t>(*p & ~(1u << w.bit));
    return;
  }
  ElemType tagType = w.tagType;
  if (w.varIsReal) {
    storeReal(p, w.varType, isFloat(tagType) ? bus.getReal(w.tag) : bus.getNumber(w.tag));
  } else if (isFloat(tagType)) {
    storeInt(p, w.varType, static_cast<int64_t>(bus.getReal(w.tag) >= 0 ? bus.getReal(w.tag) + 0.5 : bus.getReal(w.tag) - 0.5));
  } else {
    storeInt(p, w.varType, bus.getInt(w.tag));
  }
}

}  // namespace

void readVariable(const Wire& w, const uint8_t* memory, TagBus& bus) {
  const uint8_t* p = memory + w.address;
  if (w.bit >= 0) {
    bus.setBool(w.tag, (*p >> w.bit) & 1);
    return;
  }
  ElemType tagType = w.tagType;
  if (w.varIsReal) {
    double v = loadReal(p, w.varType);
    if (isFloat(tagType)) bus.setReal(w.tag, v);
    else bus.setNumber(w.tag, v);
    return;
  }
  int64_t v = loadInt(p, w.varType);
  if (isFloat(tagType)) bus.setReal(w.tag, static_cast<double>(v));
  else if (tagType == ElemType::Bool) bus.setBool(w.tag, v != 0);
  else bus.setInt(w.tag, v);
}

bool writeVariable(const Wire& w, const TagBus& bus, uint8_t* memory) {
  uint8_t* p = memory + w.address;
  uint64_t before = 0;
  std::memcpy(&before, p, w.varSize);
  storeValue(w, bus, p);
  return std::memcmp(&before, p, w.varSize) != 0;
}

Wire makeWire(TagId tag, ElemType tagType, plant::PortDir dir, const bc::VarRef& ref, ElemType varType, std::string varName) {
  Wire w;
  w.tag = tag;
  w.tagType = tagType;
  w.dir = dir;
  w.address = ref.address;
  w.bit = ref.bit;
  w.varType = varType;
  w.varSize = static_cast<uint8_t>(ref.bit >= 0 ? 1 : elemTypeInfo(varType).sizeBytes);
  w.varIsReal = isReal(varType);
  w.varName = std::move(varName);
  return w;
}

bool evaluate(const Condition& c, const uint8_t* memory) {
  if (!c.valid) return false;
  const uint8_t* p = memory + c.address;
  double v = c.bit >= 0 ? ((*p >> c.bit) & 1) : isReal(c.type) ? loadReal(p, c.type) : static_cast<double>(loadInt(p, c.type));
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
    diags.error("C020", loc, "condition '" + text + "': the PLC has no variable '" + name + "'");
    return c;
  }
  const bc::TypeDesc& t = m.types[ref->type];
  if (t.kind != bc::TypeKind::Elementary && t.kind != bc::TypeKind::Enum) {
    diags.error("C020", loc, "condition '" + text + "': '" + name + "' is not an elementary variable");
    return c;
  }
  // Parse the value with the module's own literal parser into a scratch copy of the variable.
  std::vector<uint8_t> scratch(m.memorySize(), 0);
  std::string problem = bc::writeValueFromText(m, *ref, value, scratch.data());
  if (!problem.empty()) {
    diags.error("C020", loc, "condition '" + text + "': " + problem);
    return c;
  }
  c.address = ref->address;
  c.bit = ref->bit;
  c.type = t.elem;
  c.value = c.bit >= 0 ? ((scratch[c.address] >> c.bit) & 1)
            : isReal(c.type) ? loadReal(scratch.data() + c.address, c.type)
                             : static_cast<double>(loadInt(scratch.data() + c.address, c.type));
  c.valid = true;
  return c;
}

}  // namespace virtcom::cell
