#include "core/value_codec.hpp"

#include <bit>
#include <cstring>

namespace virtcom {

int64_t loadInteger(const uint8_t* p, ElemType t) {
  switch (t) {
    case ElemType::Bool: case ElemType::Byte: case ElemType::Usint: case ElemType::Char: return *p;
    case ElemType::Sint: return static_cast<int8_t>(*p);
    case ElemType::Int: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case ElemType::Word: case ElemType::Uint: case ElemType::Wchar: { uint16_t v; std::memcpy(&v, p, 2); return v; }
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

namespace {

// Fixed-width stores that say whether the bytes changed: no library memcpy/memcmp calls, as
// every wire into the PLC takes this path every tick. Bit patterns are compared (as the bytes
// would be), so a NaN written over itself is no change.
template <typename U>
bool storeChanged(uint8_t* p, U v) {
  U before;
  std::memcpy(&before, p, sizeof(U));
  std::memcpy(p, &v, sizeof(U));
  return before != v;
}

bool storeInteger(uint8_t* p, ElemType t, int64_t v) {
  switch (elemTypeInfo(t).sizeBytes) {  // little endian: the low bytes
    case 1: return storeChanged(p, static_cast<uint8_t>(t == ElemType::Bool ? v != 0 : v));
    case 2: return storeChanged(p, static_cast<uint16_t>(v));
    case 4: return storeChanged(p, static_cast<uint32_t>(v));
    default: return storeChanged(p, static_cast<uint64_t>(v));
  }
}

bool storeReal(uint8_t* p, ElemType t, double v) {
  if (t == ElemType::Real) return storeChanged(p, std::bit_cast<uint32_t>(static_cast<float>(v)));
  return storeChanged(p, std::bit_cast<uint64_t>(v));
}

}  // namespace

void loadVariable(const uint8_t* p, int8_t bit, ElemType varType, TagBus& bus, TagId tag) {
  if (bit >= 0) {
    bus.setBool(tag, (*p >> bit) & 1);
    return;
  }
  ElemType tagType = bus.type(tag);
  if (isRealType(varType)) {
    double v = loadReal(p, varType);
    if (isFloat(tagType)) bus.setReal(tag, v);
    else bus.setNumber(tag, v);
    return;
  }
  int64_t v = loadInteger(p, varType);
  if (isFloat(tagType)) bus.setReal(tag, static_cast<double>(v));
  else if (tagType == ElemType::Bool) bus.setBool(tag, v != 0);
  else bus.setInt(tag, v);
}

bool storeVariable(uint8_t* p, int8_t bit, ElemType varType, const TagBus& bus, TagId tag) {
  if (bit >= 0) {
    uint8_t before = *p;
    if (bus.getBool(tag)) *p = static_cast<uint8_t>(*p | (1u << bit));
    else *p = static_cast<uint8_t>(*p & ~(1u << bit));
    return *p != before;
  }
  ElemType tagType = bus.type(tag);
  if (isRealType(varType)) return storeReal(p, varType, isFloat(tagType) ? bus.getReal(tag) : bus.getNumber(tag));
  if (isFloat(tagType)) {
    double r = bus.getReal(tag);
    return storeInteger(p, varType, static_cast<int64_t>(r >= 0 ? r + 0.5 : r - 0.5));
  }
  return storeInteger(p, varType, bus.getInt(tag));
}

bool wireCompatible(ElemType port, ElemType var, bool isEnum) {
  if (port == ElemType::Bool) return var == ElemType::Bool && !isEnum;
  if (var == ElemType::Bool || elemTypeInfo(var).kind == ElemKind::Text) return false;
  if (isFloat(port)) return isFloat(var) || isInteger(var);
  return isInteger(var) || isEnum || isFloat(var);
}

}  // namespace virtcom
