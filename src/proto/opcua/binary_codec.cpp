#include "proto/opcua/binary_codec.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>

namespace virtcom::proto::opcua {

namespace {

// NodeId encoding bytes (OPC 10000-6 §5.2.2.9) and ExpandedNodeId flags (§5.2.2.10).
constexpr uint8_t kTwoByte = 0x00, kFourByte = 0x01, kNumeric = 0x02, kStringId = 0x03, kGuidId = 0x04,
                  kOpaqueId = 0x05, kIdFormat = 0x0F;
constexpr uint8_t kHasNamespaceUri = 0x80, kHasServerIndex = 0x40;
// LocalizedText (§5.2.2.14) and DiagnosticInfo (§5.2.2.12) mask bits.
constexpr uint8_t kTextLocale = 0x01, kTextText = 0x02;
constexpr uint8_t kDiagSymbolicId = 0x01, kDiagNamespace = 0x02, kDiagLocalizedText = 0x04, kDiagLocale = 0x08,
                  kDiagAdditional = 0x10, kDiagInnerStatus = 0x20, kDiagInner = 0x40;

// A String or ByteString body: length -1 is null.
bool decodeBytes(Reader& r, std::string& out, bool& null) {
  int32_t n = 0;
  if (!r.i32(n)) return false;
  null = n < 0;
  if (n <= 0) {
    out.clear();
    return n >= -1;
  }
  std::span<const uint8_t> b;
  if (!r.bytes(static_cast<size_t>(n), b)) return false;
  out.assign(b.begin(), b.end());
  return true;
}

// Counts a level of nesting for the life of a decode of a recursive type.
class Nest {
 public:
  explicit Nest(Reader& r) : r_(r) { ++r_.depth; }
  ~Nest() { --r_.depth; }
  bool tooDeep() const { return r_.depth > kMaxNesting; }

 private:
  Reader& r_;
};

template <class T>
bool decodeBox(Reader& r, Box<T>& v) {
  v.value = std::make_shared<T>();
  return decode(r, *v.value);
}

template <class T>
void encodeBox(Writer& w, const Box<T>& v) {
  encode(w, v.value ? *v.value : T{});
}

}  // namespace

bool Reader::i32(int32_t& v) {
  uint32_t u = 0;
  if (!u32(u)) return false;
  v = static_cast<int32_t>(u);
  return true;
}

bool Reader::bytes(size_t n, std::span<const uint8_t>& out) {
  auto got = in_.bytes(n);
  if (!got) return false;
  out = *got;
  return true;
}

bool Reader::arrayLength(uint32_t& n, size_t minElementBytes) {
  int32_t len = 0;
  if (!i32(len) || len < -1) return false;
  n = len < 0 ? 0 : static_cast<uint32_t>(len);
  return uint64_t{n} * minElementBytes <= remaining();
}

void Writer::string(std::string_view s) { byteString(asBytes(s)); }

void Writer::byteString(std::span<const uint8_t> b) {
  i32(static_cast<int32_t>(b.size()));
  w_.bytes(b);
}

bool decode(Reader& r, bool& v) {
  uint8_t b = 0;
  if (!r.u8(b)) return false;
  v = b != 0;
  return true;
}
bool decode(Reader& r, int8_t& v) {
  uint8_t b = 0;
  if (!r.u8(b)) return false;
  v = static_cast<int8_t>(b);
  return true;
}
bool decode(Reader& r, uint8_t& v) { return r.u8(v); }
bool decode(Reader& r, int16_t& v) {
  uint16_t u = 0;
  if (!r.u16(u)) return false;
  v = static_cast<int16_t>(u);
  return true;
}
bool decode(Reader& r, uint16_t& v) { return r.u16(v); }
bool decode(Reader& r, int32_t& v) { return r.i32(v); }
bool decode(Reader& r, uint32_t& v) { return r.u32(v); }
bool decode(Reader& r, int64_t& v) {
  uint64_t u = 0;
  if (!r.u64(u)) return false;
  v = static_cast<int64_t>(u);
  return true;
}
bool decode(Reader& r, uint64_t& v) { return r.u64(v); }
bool decode(Reader& r, float& v) {
  uint32_t u = 0;
  if (!r.u32(u)) return false;
  v = std::bit_cast<float>(u);
  return true;
}
bool decode(Reader& r, double& v) {
  uint64_t u = 0;
  if (!r.u64(u)) return false;
  v = std::bit_cast<double>(u);
  return true;
}
bool decode(Reader& r, String& v) { return decodeBytes(r, v.text, v.null); }
bool decode(Reader& r, std::string& v) {
  bool null = false;
  return decodeBytes(r, v, null);
}
bool decode(Reader& r, DateTime& v) { return decode(r, v.ticks); }
bool decode(Reader& r, Guid& v) {
  std::span<const uint8_t> tail;
  if (!r.u32(v.data1) || !r.u16(v.data2) || !r.u16(v.data3) || !r.bytes(8, tail)) return false;
  std::copy(tail.begin(), tail.end(), v.data4.begin());
  return true;
}
bool decode(Reader& r, ByteString& v) { return decodeBytes(r, v.bytes, v.null); }
bool decode(Reader& r, XmlElement& v) { return decode(r, v.text); }

namespace {

// The NodeId after its encoding byte (whose flag bits an ExpandedNodeId uses).
bool decodeNodeIdBody(Reader& r, uint8_t format, NodeId& v) {
  v = NodeId{};
  switch (format & kIdFormat) {
    case kTwoByte: {
      uint8_t id = 0;
      if (!r.u8(id)) return false;
      v.numeric = id;
      return true;
    }
    case kFourByte: {
      uint8_t ns = 0;
      uint16_t id = 0;
      if (!r.u8(ns) || !r.u16(id)) return false;
      v.ns = ns;
      v.numeric = id;
      return true;
    }
    case kNumeric: return r.u16(v.ns) && r.u32(v.numeric);
    case kStringId: v.kind = NodeId::Kind::String; return r.u16(v.ns) && decode(r, v.text);
    case kGuidId: v.kind = NodeId::Kind::Guid; return r.u16(v.ns) && decode(r, v.guid);
    case kOpaqueId: v.kind = NodeId::Kind::Opaque; return r.u16(v.ns) && decode(r, v.text);
    default: return false;
  }
}

}  // namespace

bool decode(Reader& r, NodeId& v) {
  uint8_t format = 0;
  // A plain NodeId has no flag bits.
  return r.u8(format) && (format & ~kIdFormat) == 0 && decodeNodeIdBody(r, format, v);
}

bool decode(Reader& r, ExpandedNodeId& v) {
  uint8_t format = 0;
  if (!r.u8(format) || (format & 0x30) != 0 || !decodeNodeIdBody(r, format, v.id)) return false;
  v.namespaceUri.clear();
  v.serverIndex = 0;
  if ((format & kHasNamespaceUri) && !decode(r, v.namespaceUri)) return false;
  if ((format & kHasServerIndex) && !r.u32(v.serverIndex)) return false;
  return true;
}

bool decode(Reader& r, StatusCode& v) { return r.u32(v.code); }
bool decode(Reader& r, QualifiedName& v) { return r.u16(v.ns) && decode(r, v.name); }

bool decode(Reader& r, LocalizedText& v) {
  uint8_t mask = 0;
  if (!r.u8(mask)) return false;
  v = LocalizedText{};
  if ((mask & kTextLocale) && !decode(r, v.locale)) return false;
  if ((mask & kTextText) && !decode(r, v.text)) return false;
  return true;
}

bool decode(Reader& r, ExtensionObject& v) {
  uint8_t body = 0;
  if (!decode(r, v.typeId) || !r.u8(body) || body > 2) return false;
  v.body = static_cast<ExtensionObject::Body>(body);
  v.bytes.clear();
  return body == 0 || decode(r, v.bytes);
}

bool decode(Reader& r, DataValueBox& v) { return decodeBox(r, v); }
bool decode(Reader& r, VariantBox& v) { return decodeBox(r, v); }
bool decode(Reader& r, DiagnosticInfoBox& v) { return decodeBox(r, v); }

bool decodeScalar(Reader& r, BuiltinType type, Scalar& out) {
  switch (type) {
#define X(name, id, cpp)            \
  case BuiltinType::name: {         \
    cpp value{};                    \
    if (!decode(r, value)) return false; \
    out = std::move(value);         \
    return true;                    \
  }
#include "proto/opcua/builtin_types.def"
#undef X
    case BuiltinType::Null: out = std::monostate{}; return true;
  }
  return false;
}

bool decode(Reader& r, Variant& v) {
  Nest nest(r);
  uint8_t mask = 0;
  if (nest.tooDeep() || !r.u8(mask)) return false;
  const uint8_t id = mask & kVariantTypeMask;
  if (id > static_cast<uint8_t>(BuiltinType::DiagnosticInfo)) return false;
  v = Variant{};
  v.type = static_cast<BuiltinType>(id);
  v.isArray = (mask & kVariantArray) != 0;
  if (!v.isArray) {
    if (v.type == BuiltinType::Null) return true;
    v.values.resize(1);
    return decodeScalar(r, v.type, v.values[0]);
  }
  uint32_t n = 0;
  if (!r.arrayLength(n, v.type == BuiltinType::Null ? 0 : 1)) return false;
  if (v.type == BuiltinType::Null && n > 0) return false;
  v.values.resize(n);
  for (auto& e : v.values)
    if (!decodeScalar(r, v.type, e)) return false;
  if (mask & kVariantDimensions) {
    uint32_t rank = 0;
    if (!r.arrayLength(rank, 4)) return false;
    v.dimensions.resize(rank);
    for (auto& d : v.dimensions)
      if (!r.i32(d)) return false;
  }
  return true;
}

bool decode(Reader& r, DataValue& v) {
  Nest nest(r);
  uint8_t mask = 0;
  if (nest.tooDeep() || !r.u8(mask)) return false;
  v = DataValue{};
  v.hasValue = mask & kDataValueValue;
  v.hasStatus = mask & kDataValueStatus;
  v.hasSourceTime = mask & kDataValueSourceTime;
  v.hasServerTime = mask & kDataValueServerTime;
  if (v.hasValue && !decode(r, v.value)) return false;
  if (v.hasStatus && !r.u32(v.status)) return false;
  if (v.hasSourceTime && !decode(r, v.sourceTime)) return false;
  if ((mask & kDataValueSourcePico) && !r.u16(v.sourcePicoseconds)) return false;
  if (v.hasServerTime && !decode(r, v.serverTime)) return false;
  if ((mask & kDataValueServerPico) && !r.u16(v.serverPicoseconds)) return false;
  return true;
}

bool decode(Reader& r, DiagnosticInfo& v) {
  Nest nest(r);
  uint8_t mask = 0;
  if (nest.tooDeep() || !r.u8(mask)) return false;
  v = DiagnosticInfo{};
  if ((mask & kDiagSymbolicId) && !r.i32(v.symbolicId)) return false;
  if ((mask & kDiagNamespace) && !r.i32(v.namespaceUri)) return false;
  if ((mask & kDiagLocale) && !r.i32(v.locale)) return false;
  if ((mask & kDiagLocalizedText) && !r.i32(v.localizedText)) return false;
  v.hasAdditionalInfo = mask & kDiagAdditional;
  if (v.hasAdditionalInfo && !decode(r, v.additionalInfo)) return false;
  v.hasInnerStatus = mask & kDiagInnerStatus;
  if (v.hasInnerStatus && !r.u32(v.innerStatus)) return false;
  if (mask & kDiagInner) {
    v.inner = std::make_shared<DiagnosticInfo>();
    if (!decode(r, *v.inner)) return false;
  }
  return true;
}

void encode(Writer& w, bool v) { w.u8(v ? 1 : 0); }
void encode(Writer& w, int8_t v) { w.u8(static_cast<uint8_t>(v)); }
void encode(Writer& w, uint8_t v) { w.u8(v); }
void encode(Writer& w, int16_t v) { w.u16(static_cast<uint16_t>(v)); }
void encode(Writer& w, uint16_t v) { w.u16(v); }
void encode(Writer& w, int32_t v) { w.i32(v); }
void encode(Writer& w, uint32_t v) { w.u32(v); }
void encode(Writer& w, int64_t v) { w.u64(static_cast<uint64_t>(v)); }
void encode(Writer& w, uint64_t v) { w.u64(v); }
void encode(Writer& w, float v) { w.u32(std::bit_cast<uint32_t>(v)); }
void encode(Writer& w, double v) { w.u64(std::bit_cast<uint64_t>(v)); }
void encode(Writer& w, const String& v) {
  if (v.null) w.nullString();
  else w.string(v.text);
}
void encode(Writer& w, std::string_view v) { w.string(v); }
void encode(Writer& w, DateTime v) { encode(w, v.ticks); }
void encode(Writer& w, const Guid& v) {
  w.u32(v.data1);
  w.u16(v.data2);
  w.u16(v.data3);
  w.raw(v.data4);
}
void encode(Writer& w, const ByteString& v) {
  if (v.null) w.nullString();
  else w.string(v.bytes);
}
void encode(Writer& w, const XmlElement& v) { w.string(v.text); }

namespace {

// The NodeId with its first byte or'ed with `flags` (ExpandedNodeId).
void encodeNodeId(Writer& w, const NodeId& v, uint8_t flags) {
  switch (v.kind) {
    case NodeId::Kind::Numeric:
      if (v.ns == 0 && v.numeric <= 0xFF) {
        w.u8(kTwoByte | flags);
        w.u8(static_cast<uint8_t>(v.numeric));
      } else if (v.ns <= 0xFF && v.numeric <= 0xFFFF) {
        w.u8(kFourByte | flags);
        w.u8(static_cast<uint8_t>(v.ns));
        w.u16(static_cast<uint16_t>(v.numeric));
      } else {
        w.u8(kNumeric | flags);
        w.u16(v.ns);
        w.u32(v.numeric);
      }
      return;
    case NodeId::Kind::String:
      w.u8(kStringId | flags);
      w.u16(v.ns);
      w.string(v.text);
      return;
    case NodeId::Kind::Guid:
      w.u8(kGuidId | flags);
      w.u16(v.ns);
      encode(w, v.guid);
      return;
    case NodeId::Kind::Opaque:
      w.u8(kOpaqueId | flags);
      w.u16(v.ns);
      w.string(v.text);
      return;
  }
}

}  // namespace

void encode(Writer& w, const NodeId& v) { encodeNodeId(w, v, 0); }
void encode(Writer& w, const ExpandedNodeId& v) {
  const uint8_t flags = static_cast<uint8_t>((v.namespaceUri.empty() ? 0 : kHasNamespaceUri) | (v.serverIndex ? kHasServerIndex : 0));
  encodeNodeId(w, v.id, flags);
  if (!v.namespaceUri.empty()) w.string(v.namespaceUri);
  if (v.serverIndex) w.u32(v.serverIndex);
}
void encode(Writer& w, StatusCode v) { w.u32(v.code); }
void encode(Writer& w, const QualifiedName& v) {
  w.u16(v.ns);
  w.string(v.name);
}
void encode(Writer& w, const LocalizedText& v) {
  w.u8(static_cast<uint8_t>((v.locale.empty() ? 0 : kTextLocale) | (v.text.empty() ? 0 : kTextText)));
  if (!v.locale.empty()) w.string(v.locale);
  if (!v.text.empty()) w.string(v.text);
}
void encode(Writer& w, const ExtensionObject& v) {
  encode(w, v.typeId);
  w.u8(static_cast<uint8_t>(v.body));
  if (v.body != ExtensionObject::Body::None) w.string(v.bytes);
}
void encode(Writer& w, const DataValueBox& v) { encodeBox(w, v); }
void encode(Writer& w, const VariantBox& v) { encodeBox(w, v); }
void encode(Writer& w, const DiagnosticInfoBox& v) { encodeBox(w, v); }

void encodeScalar(Writer& w, const Scalar& v) {
  std::visit(
      [&w](const auto& x) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(x)>, std::monostate>) encode(w, x);
      },
      v);
}

void encode(Writer& w, const Variant& v) {
  uint8_t mask = static_cast<uint8_t>(v.type);
  if (v.isArray) mask |= kVariantArray;
  if (v.isArray && !v.dimensions.empty()) mask |= kVariantDimensions;
  w.u8(mask);
  if (v.isArray) w.i32(static_cast<int32_t>(v.values.size()));
  for (const Scalar& s : v.values) encodeScalar(w, s);
  if (mask & kVariantDimensions) {
    w.i32(static_cast<int32_t>(v.dimensions.size()));
    for (int32_t d : v.dimensions) w.i32(d);
  }
}

void encode(Writer& w, const DataValue& v) {
  uint8_t mask = 0;
  if (v.hasValue) mask |= kDataValueValue;
  if (v.hasStatus) mask |= kDataValueStatus;
  if (v.hasSourceTime) mask |= kDataValueSourceTime;
  if (v.hasServerTime) mask |= kDataValueServerTime;
  if (v.hasSourceTime && v.sourcePicoseconds) mask |= kDataValueSourcePico;
  if (v.hasServerTime && v.serverPicoseconds) mask |= kDataValueServerPico;
  w.u8(mask);
  if (v.hasValue) encode(w, v.value);
  if (v.hasStatus) w.u32(v.status);
  if (v.hasSourceTime) encode(w, v.sourceTime);
  if (mask & kDataValueSourcePico) w.u16(v.sourcePicoseconds);
  if (v.hasServerTime) encode(w, v.serverTime);
  if (mask & kDataValueServerPico) w.u16(v.serverPicoseconds);
}

void encode(Writer& w, const DiagnosticInfo& v) {
  uint8_t mask = 0;
  if (v.symbolicId >= 0) mask |= kDiagSymbolicId;
  if (v.namespaceUri >= 0) mask |= kDiagNamespace;
  if (v.localizedText >= 0) mask |= kDiagLocalizedText;
  if (v.locale >= 0) mask |= kDiagLocale;
  if (v.hasAdditionalInfo) mask |= kDiagAdditional;
  if (v.hasInnerStatus) mask |= kDiagInnerStatus;
  if (v.inner) mask |= kDiagInner;
  w.u8(mask);
  if (v.symbolicId >= 0) w.i32(v.symbolicId);
  if (v.namespaceUri >= 0) w.i32(v.namespaceUri);
  if (v.locale >= 0) w.i32(v.locale);
  if (v.localizedText >= 0) w.i32(v.localizedText);
  if (v.hasAdditionalInfo) w.string(v.additionalInfo);
  if (v.hasInnerStatus) w.u32(v.innerStatus);
  if (v.inner) encode(w, *v.inner);
}

}  // namespace virtcom::proto::opcua
