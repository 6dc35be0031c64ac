#pragma once
// The OPC UA built-in types as values (docs/opcua.md, Wire reference: Built-in types). What the
// table builtin_types.def lists, and nothing that knows a service: the codec (binary_codec.hpp)
// reads and writes them, the services (services.def) are built from them.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace virtcom::proto::opcua {

enum class BuiltinType : uint8_t {
  Null = 0,
#define X(name, id, cpp) name = id,
#include "proto/opcua/builtin_types.def"
#undef X
};
// "Int32" for BuiltinType::Int32; "Null" for 0 and ids outside the table.
const char* builtinTypeName(BuiltinType t);

enum class StatusCodeValue : uint32_t {
#define X(name, code) name = code,
#include "proto/opcua/status_codes.def"
#undef X
};
// "BadNodeIdUnknown"; "0x8abc0000" style text for codes outside the table.
std::string statusName(uint32_t code);
inline bool isBad(uint32_t code) { return (code & 0x80000000u) != 0; }

// The bytes a byte-like built-in holds in its std::string, without a copy.
inline std::span<const uint8_t> asBytes(std::string_view s) { return {reinterpret_cast<const uint8_t*>(s.data()), s.size()}; }

// Wrappers give the byte-like built-ins distinct C++ types, so a Scalar's index is its type id.
struct String {
  std::string text;
  bool null = false;  // length -1 on the wire (distinct from "")
  bool operator==(const String&) const = default;
};
struct ByteString {
  std::string bytes;
  bool null = false;
  std::span<const uint8_t> view() const { return asBytes(bytes); }
  bool operator==(const ByteString&) const = default;
};
struct XmlElement {
  std::string text;
  bool operator==(const XmlElement&) const = default;
};
// 100 ns intervals since 1601-01-01 UTC.
struct DateTime {
  int64_t ticks = 0;
  bool operator==(const DateTime&) const = default;
};
struct StatusCode {
  uint32_t code = 0;
  bool operator==(const StatusCode&) const = default;
};
struct Guid {
  uint32_t data1 = 0;
  uint16_t data2 = 0, data3 = 0;
  std::array<uint8_t, 8> data4{};
  bool operator==(const Guid&) const = default;
};

struct NodeId {
  enum class Kind : uint8_t { Numeric, String, Guid, Opaque };
  uint16_t ns = 0;
  Kind kind = Kind::Numeric;
  uint32_t numeric = 0;
  std::string text;  // String: the name; Opaque: the bytes
  opcua::Guid guid;
  static NodeId num(uint16_t ns, uint32_t id) { return NodeId{ns, Kind::Numeric, id, {}, {}}; }
  static NodeId str(uint16_t ns, std::string s) { return NodeId{ns, Kind::String, 0, std::move(s), {}}; }
  bool isNull() const { return ns == 0 && kind == Kind::Numeric && numeric == 0; }
  bool operator==(const NodeId&) const = default;
};
// "i=85", "ns=4;s=|var|...", "ns=1;g=...", "ns=2;b=<hex>" (OPC 10000-6 §5.3.1.10).
std::string formatNodeId(const NodeId& id);
// The numeric and string forms back ("i=85", "ns=4;s=|var|virtcom.Application.MAIN.x"); nullopt
// for anything else (a namespace over 65535, an empty string id, g= and b= forms).
std::optional<NodeId> parseNodeId(std::string_view text);

struct ExpandedNodeId {
  NodeId id;
  std::string namespaceUri;  // empty: absent
  uint32_t serverIndex = 0;
  bool operator==(const ExpandedNodeId&) const = default;
};
struct QualifiedName {
  uint16_t ns = 0;
  std::string name;
  bool operator==(const QualifiedName&) const = default;
};
struct LocalizedText {
  std::string locale, text;  // empty: absent
  bool operator==(const LocalizedText&) const = default;
};
struct ExtensionObject {
  enum class Body : uint8_t { None = 0, Binary = 1, Xml = 2 };
  NodeId typeId;
  Body body = Body::None;
  std::string bytes;
  std::span<const uint8_t> view() const { return asBytes(bytes); }
  bool operator==(const ExtensionObject&) const = default;
};

struct DataValue;
struct Variant;
struct DiagnosticInfo;
// The recursive built-ins inside a Scalar (a Variant may hold a DataValue holding a Variant...).
template <class T>
struct Box {
  std::shared_ptr<T> value;
  bool operator==(const Box& o) const { return value == o.value || (value && o.value && *value == *o.value); }
};
using DataValueBox = Box<DataValue>;
using VariantBox = Box<Variant>;
using DiagnosticInfoBox = Box<DiagnosticInfo>;

// One value of any built-in type; index = BuiltinType id (0: Null).
using Scalar = std::variant<std::monostate
#define X(name, id, cpp) , cpp
#include "proto/opcua/builtin_types.def"
#undef X
                            >;

// A scalar or a (multi-dimensional) array of one built-in type (OPC 10000-6 §5.2.2.16).
struct Variant {
  BuiltinType type = BuiltinType::Null;
  bool isArray = false;
  std::vector<Scalar> values;        // one for a scalar, none for Null
  std::vector<int32_t> dimensions;   // arrays of rank > 1 only
  static Variant scalar(Scalar s);
  bool operator==(const Variant&) const = default;
};

struct DataValue {
  bool hasValue = false, hasStatus = false, hasSourceTime = false, hasServerTime = false;
  Variant value;
  uint32_t status = 0;
  DateTime sourceTime, serverTime;
  uint16_t sourcePicoseconds = 0, serverPicoseconds = 0;  // present when non-zero
  bool operator==(const DataValue&) const = default;
};

// Every field optional (mask bits); -1: absent.
struct DiagnosticInfo {
  int32_t symbolicId = -1, namespaceUri = -1, localizedText = -1, locale = -1;
  std::string additionalInfo;
  bool hasAdditionalInfo = false, hasInnerStatus = false;
  uint32_t innerStatus = 0;
  std::shared_ptr<DiagnosticInfo> inner;
  bool operator==(const DiagnosticInfo& o) const;
};

}  // namespace virtcom::proto::opcua
