#pragma once
// A signal's raw tag-bus value (core/tag_bus.hpp: BOOL 0/1, integers sign- or zero-extended by
// kind, REAL/LREAL as double bits) as a number, for whatever plots or compares recorded values
// (the report's charts, the historian's decimated series).
#include <bit>
#include <cstdint>

#include "core/iec_value.hpp"

namespace virtcom {

inline double signalNumber(ElemType type, uint64_t raw) {
  if (type == ElemType::Bool) return raw != 0 ? 1.0 : 0.0;
  if (isFloat(type)) return std::bit_cast<double>(raw);
  ElemKind kind = elemTypeInfo(type).kind;
  if (isZeroExtendedKind(kind)) return static_cast<double>(raw);
  return static_cast<double>(static_cast<int64_t>(raw));
}

}  // namespace virtcom
