#pragma once
// Typed transfers between the bytes of an elementary PLC variable (little endian, as the PLC's
// memory image and the ADS wire hold them) and a tag on the bus, with the conversions the
// wiring allows (docs/cell-file.md): integers, reals and enums convert numerically, reals are
// rounded into integers, BOOL stays BOOL. Used by the soft PLC's wiring (cell) and by the ADS
// client bridge. Nothing here allocates.
#include <cstdint>

#include "core/iec_value.hpp"
#include "core/tag_bus.hpp"

namespace virtcom {

// The variable at `p` (storage type `varType`; `bit` >= 0: one bit of the byte at `p`) into `tag`.
void loadVariable(const uint8_t* p, int8_t bit, ElemType varType, TagBus& bus, TagId tag);
// `tag` into the variable at `p`; true if its bytes changed.
bool storeVariable(uint8_t* p, int8_t bit, ElemType varType, const TagBus& bus, TagId tag);

// The variable at `p` as an integer / a real, by its storage type (not BOOL bits, not strings).
int64_t loadInteger(const uint8_t* p, ElemType varType);
double loadReal(const uint8_t* p, ElemType varType);  // REAL or LREAL
inline bool isRealType(ElemType t) { return t == ElemType::Real || t == ElemType::Lreal; }

// Whether a device port of type `port` may be wired to a variable of elementary type `var`
// (`isEnum`: an enumeration stored as `var`): BOOL only to BOOL; numbers to numbers and enums;
// never to strings.
bool wireCompatible(ElemType port, ElemType var, bool isEnum = false);

}  // namespace virtcom
