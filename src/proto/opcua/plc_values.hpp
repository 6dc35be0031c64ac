#pragma once
// PLC variables as OPC UA values: bytes of the published memory image encoded as a Variant
// straight into a response (no intermediate Variant: reads and notifications allocate nothing
// beyond the response buffer), and a written Variant turned into the bytes the next scan takes.
// Numbers are little endian both in the image and on the wire, so they copy as they are.
#include <cstdint>
#include <span>
#include <vector>

#include "proto/opcua/address_space.hpp"
#include "proto/opcua/binary_codec.hpp"

namespace virtcom::proto::opcua {

// Appends the Variant of `v` read from `image` (which must hold the variable).
void encodePlcVariant(Writer& w, const PlcValue& v, std::span<const uint8_t> image);
// True if the variable's bytes differ between two images (or, with `deadband` > 0, if a numeric
// scalar moved by more than it: OPC 10000-4 §7.22.2, absolute deadband).
bool plcValueChanged(const PlcValue& v, std::span<const uint8_t> before, std::span<const uint8_t> now, double deadband);

// The bytes `value` writes into the variable (elementSize * count; one 0/1 byte for a bit), or
// a Bad status: BadTypeMismatch (other built-in type, scalar for array or the reverse, other
// element count), BadOutOfRange (a string longer than the STRING's length).
uint32_t plcBytesOf(const Variant& value, const PlcValue& v, std::vector<uint8_t>& out);

}  // namespace virtcom::proto::opcua
