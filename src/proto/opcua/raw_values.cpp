#include "proto/opcua/raw_values.hpp"

#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

std::optional<ElemType> elemTypeOfBuiltin(BuiltinType t) {
  switch (t) {
    case BuiltinType::Boolean: return ElemType::Bool;
    case BuiltinType::SByte: return ElemType::Sint;
    case BuiltinType::Byte: return ElemType::Usint;
    case BuiltinType::Int16: return ElemType::Int;
    case BuiltinType::UInt16: return ElemType::Uint;
    case BuiltinType::Int32: return ElemType::Dint;
    case BuiltinType::UInt32: return ElemType::Udint;
    case BuiltinType::Int64: return ElemType::Lint;
    case BuiltinType::UInt64: return ElemType::Ulint;
    case BuiltinType::Float: return ElemType::Real;
    case BuiltinType::Double: return ElemType::Lreal;
    default: return std::nullopt;
  }
}

void encodeReadValueId(Writer& w, std::span<const uint8_t> node, uint32_t attribute) {
  w.raw(node);
  w.u32(attribute);
  w.nullString();  // IndexRange
  w.u16(0);        // DataEncoding: NamespaceIndex
  w.nullString();  //               Name
}

void encodeWriteValue(Writer& w, std::span<const uint8_t> node, BuiltinType wire, std::span<const uint8_t> value) {
  w.raw(node);
  w.u32(kValueAttr);
  w.nullString();  // IndexRange
  w.u8(kDataValueValue);
  w.u8(static_cast<uint8_t>(wire));
  w.raw(value);
}

bool readRawValue(Reader& r, RawValue& out) {
  out = RawValue{};
  uint8_t mask = 0, variant = 0;
  if (!r.u8(mask)) return false;
  if (mask & kDataValueValue) {
    if (!r.u8(variant)) return false;
    out.type = static_cast<BuiltinType>(variant & kVariantTypeMask);
    out.isArray = (variant & kVariantArray) != 0;
    auto elem = elemTypeOfBuiltin(out.type);
    if (out.isArray || (!elem && out.type != BuiltinType::Null)) return true;
    if (elem && !r.bytes(elemTypeInfo(*elem).sizeBytes, out.bytes)) return false;
  }
  if ((mask & kDataValueStatus) && !r.u32(out.status)) return false;
  uint64_t time = 0;
  uint16_t pico = 0;
  if ((mask & kDataValueSourceTime) && !r.u64(time)) return false;
  if ((mask & kDataValueSourcePico) && !r.u16(pico)) return false;
  if ((mask & kDataValueServerTime) && !r.u64(time)) return false;
  if ((mask & kDataValueServerPico) && !r.u16(pico)) return false;
  return true;
}

}  // namespace virtcom::proto::opcua
