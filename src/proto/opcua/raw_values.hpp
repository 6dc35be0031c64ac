#pragma once
// The client bridge's values on the wire without Variants (docs/opcua.md, The client bridge):
// the ReadValueId and WriteValue of a node's attribute, and a DataValue of a Read response read
// as the bytes of its Boolean or numeric scalar. Pure: no sockets; nothing is allocated.
#include <cstdint>
#include <optional>
#include <span>

#include "core/iec_value.hpp"
#include "proto/opcua/binary_codec.hpp"

namespace virtcom::proto::opcua {

inline constexpr uint32_t kTimestampsNeither = 3;  // TimestampsToReturn (OPC 10000-4 §7.40)

// The elementary type a scalar of built-in type `t` holds as the same bytes (Boolean: BOOL,
// Int16: INT, Double: LREAL, ...); nullopt for strings and the structured built-ins.
std::optional<ElemType> elemTypeOfBuiltin(BuiltinType t);

// A ReadValueId (OPC 10000-4 §7.29) of `attribute` of the node whose NodeId is `node` (encoded):
// no IndexRange, and the DataEncoding a null QualifiedName (a null name, not an empty one: a
// server may take an empty name as an encoding asked for, and node-opcua then refuses every
// attribute but Value with BadDataEncodingInvalid).
void encodeReadValueId(Writer& w, std::span<const uint8_t> node, uint32_t attribute);
// A WriteValue (OPC 10000-4 §5.10.4.2) of the node's Value: a DataValue of only a scalar Variant
// of type `wire` whose bytes are `value` (little endian, as the built-in type encodes).
void encodeWriteValue(Writer& w, std::span<const uint8_t> node, BuiltinType wire, std::span<const uint8_t> value);

// One DataValue of a Read response: its status (Good when absent), its type and, for a Boolean
// or numeric scalar, the bytes of its value (a view into the response).
struct RawValue {
  uint32_t status = 0;
  BuiltinType type = BuiltinType::Null;
  bool isArray = false;
  std::span<const uint8_t> bytes;
  // Read to its end (no value, or a Boolean or numeric scalar): the reader is at the next one.
  bool wholly() const { return !isArray && (type == BuiltinType::Null || !bytes.empty()); }
};
// Reads one DataValue into `out`; false if it is malformed. An array or a value of another type
// (a String, a structure) is returned with empty bytes and the reader left inside it: the rest
// of the response cannot be found, so the caller reports it and reads no further.
bool readRawValue(Reader& r, RawValue& out);

}  // namespace virtcom::proto::opcua
