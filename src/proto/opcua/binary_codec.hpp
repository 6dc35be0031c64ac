#pragma once
// OPC UA binary encoding of the built-in types (docs/opcua.md, Wire reference: Built-in types;
// OPC 10000-6 §5.2). Little endian through the ADS stack's bounds-checked reader and writer. A
// decode never reads past its span: it returns false (and the service answers BadDecodingError).
// Nested Variants, DataValues and DiagnosticInfos are cut at kMaxNesting levels, arrays at the
// reader's remaining bytes, so hostile input cannot make the decoder recurse or allocate without
// bound.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "proto/ads/byte_io.hpp"
#include "proto/opcua/types.hpp"

namespace virtcom::proto::opcua {

inline constexpr int kMaxNesting = 16;

class Reader {
 public:
  explicit Reader(std::span<const uint8_t> bytes) : in_(bytes) {}
  bool u8(uint8_t& v) { return take(in_.u8(), v); }
  bool u16(uint16_t& v) { return take(in_.u16(), v); }
  bool u32(uint32_t& v) { return take(in_.u32(), v); }
  bool u64(uint64_t& v) { return take(in_.u64(), v); }
  bool i32(int32_t& v);
  bool bytes(size_t n, std::span<const uint8_t>& out);
  // An array length: -1 (null) reads as 0; false if negative otherwise or if more elements than
  // remaining bytes could hold (each element takes at least `minElementBytes`).
  bool arrayLength(uint32_t& n, size_t minElementBytes = 1);
  size_t remaining() const { return in_.remaining(); }
  std::span<const uint8_t> rest() const { return in_.rest(); }
  int depth = 0;  // nesting of Variant / DataValue / DiagnosticInfo being decoded

 private:
  template <class T>
  static bool take(std::optional<T> got, T& v) {
    if (!got) return false;
    v = *got;
    return true;
  }
  ads::LittleEndianReader in_;
};

class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(out), w_(out) {}
  void u8(uint8_t v) { w_.u8(v); }
  void u16(uint16_t v) { w_.u16(v); }
  void u32(uint32_t v) { w_.u32(v); }
  void u64(uint64_t v) { w_.u64(v); }
  void i32(int32_t v) { w_.u32(static_cast<uint32_t>(v)); }
  void raw(std::span<const uint8_t> b) { w_.bytes(b); }
  // A String / ByteString body: int32 length, then the bytes.
  void string(std::string_view s);
  void byteString(std::span<const uint8_t> b);
  void nullString() { i32(-1); }
  size_t size() const { return out_.size(); }
  void put32(size_t at, uint32_t v) { w_.put32(at, v); }
  std::vector<uint8_t>& buffer() { return out_; }

 private:
  std::vector<uint8_t>& out_;
  ads::LittleEndianWriter w_;
};

// One overload per built-in (the C++ types of builtin_types.def).
bool decode(Reader& r, bool& v);
bool decode(Reader& r, int8_t& v);
bool decode(Reader& r, uint8_t& v);
bool decode(Reader& r, int16_t& v);
bool decode(Reader& r, uint16_t& v);
bool decode(Reader& r, int32_t& v);
bool decode(Reader& r, uint32_t& v);
bool decode(Reader& r, int64_t& v);
bool decode(Reader& r, uint64_t& v);
bool decode(Reader& r, float& v);
bool decode(Reader& r, double& v);
bool decode(Reader& r, String& v);
bool decode(Reader& r, DateTime& v);
bool decode(Reader& r, Guid& v);
bool decode(Reader& r, ByteString& v);
bool decode(Reader& r, XmlElement& v);
bool decode(Reader& r, NodeId& v);
bool decode(Reader& r, ExpandedNodeId& v);
bool decode(Reader& r, StatusCode& v);
bool decode(Reader& r, QualifiedName& v);
bool decode(Reader& r, LocalizedText& v);
bool decode(Reader& r, ExtensionObject& v);
bool decode(Reader& r, DataValueBox& v);
bool decode(Reader& r, VariantBox& v);
bool decode(Reader& r, DiagnosticInfoBox& v);
bool decode(Reader& r, Variant& v);
bool decode(Reader& r, DataValue& v);
bool decode(Reader& r, DiagnosticInfo& v);
// A string whose nullness does not matter (names, URLs).
bool decode(Reader& r, std::string& v);

void encode(Writer& w, bool v);
void encode(Writer& w, int8_t v);
void encode(Writer& w, uint8_t v);
void encode(Writer& w, int16_t v);
void encode(Writer& w, uint16_t v);
void encode(Writer& w, int32_t v);
void encode(Writer& w, uint32_t v);
void encode(Writer& w, int64_t v);
void encode(Writer& w, uint64_t v);
void encode(Writer& w, float v);
void encode(Writer& w, double v);
void encode(Writer& w, const String& v);
void encode(Writer& w, DateTime v);
void encode(Writer& w, const Guid& v);
void encode(Writer& w, const ByteString& v);
void encode(Writer& w, const XmlElement& v);
void encode(Writer& w, const NodeId& v);
void encode(Writer& w, const ExpandedNodeId& v);
void encode(Writer& w, StatusCode v);
void encode(Writer& w, const QualifiedName& v);
void encode(Writer& w, const LocalizedText& v);
void encode(Writer& w, const ExtensionObject& v);
void encode(Writer& w, const DataValueBox& v);
void encode(Writer& w, const VariantBox& v);
void encode(Writer& w, const DiagnosticInfoBox& v);
void encode(Writer& w, const Variant& v);
void encode(Writer& w, const DataValue& v);
void encode(Writer& w, const DiagnosticInfo& v);
void encode(Writer& w, std::string_view v);

// Scalars by type id (the table's dispatch): decode one value of `type` into `out`.
bool decodeScalar(Reader& r, BuiltinType type, Scalar& out);
void encodeScalar(Writer& w, const Scalar& v);

// DataValue mask bits (OPC 10000-6 §5.2.2.17) and Variant mask bits (§5.2.2.16).
inline constexpr uint8_t kDataValueValue = 0x01, kDataValueStatus = 0x02, kDataValueSourceTime = 0x04,
                         kDataValueServerTime = 0x08, kDataValueSourcePico = 0x10, kDataValueServerPico = 0x20;
inline constexpr uint8_t kVariantArray = 0x80, kVariantDimensions = 0x40, kVariantTypeMask = 0x3F;

}  // namespace virtcom::proto::opcua
