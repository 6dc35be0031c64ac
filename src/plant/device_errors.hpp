#pragma once
// Device error codes (the `error` output of every sequenced device), from device_errors.def.
#include <cstdint>

namespace virtcom::plant {

enum class DeviceError : int32_t {
#define X(e, code, meaning) e = code,
#include "plant/device_errors.def"
#undef X
};

constexpr int32_t code(DeviceError e) { return static_cast<int32_t>(e); }
// One line of meaning for a code; "unknown error code" for codes not in the table.
const char* deviceErrorMeaning(int32_t code);

}  // namespace virtcom::plant
