#pragma once
// Register slots and little-endian memory access shared by the dispatch loop and the natives.
// A register is a raw 64-bit slot; these helpers give it the i64 / u64 / f64 view that an
// instruction asks for, without undefined behaviour.
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace virtcom::vm {

inline int64_t asI(uint64_t v) { return static_cast<int64_t>(v); }
inline double asF(uint64_t v) { return std::bit_cast<double>(v); }
inline uint64_t fromI(int64_t v) { return static_cast<uint64_t>(v); }
inline uint64_t fromF(double v) { return std::bit_cast<uint64_t>(v); }

// Reads a T stored little endian at p (any alignment).
template <typename T>
inline T loadLe(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) {
    if constexpr (std::is_floating_point_v<T>) {
      using U = std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>;
      return std::bit_cast<T>(std::byteswap(std::bit_cast<U>(v)));
    } else {
      return std::byteswap(v);
    }
  }
  return v;
}

// Writes v little endian at p (any alignment).
template <typename T>
inline void storeLe(uint8_t* p, T v) {
  if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) {
    if constexpr (std::is_floating_point_v<T>) {
      using U = std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>;
      v = std::bit_cast<T>(std::byteswap(std::bit_cast<U>(v)));
    } else {
      v = std::byteswap(v);
    }
  }
  std::memcpy(p, &v, sizeof v);
}

// True (and addr set) when [base + offset, base + offset + width) lies inside
// [kNullGuard, memorySize); no wrap-around is possible.
inline bool checkedAddress(uint64_t base, uint64_t offset, uint64_t width, uint64_t memorySize,
                           uint64_t nullGuard, uint64_t& addr) {
  addr = base + offset;
  if (addr < base || addr < nullGuard || memorySize < width) return false;
  return addr <= memorySize - width;
}

// Round half away from zero, saturated to i64; NaN -> 0 (F2I).
inline int64_t roundToI64(double f) {
  if (f != f) return 0;
  double r = std::round(f);
  if (r >= 9223372036854775808.0) return INT64_MAX;
  if (r < -9223372036854775808.0) return INT64_MIN;
  return static_cast<int64_t>(r);
}

// Truncate toward zero, saturated to i64; NaN -> 0 (F2I_TRUNC).
inline int64_t truncToI64(double f) {
  if (f != f) return 0;
  double r = std::trunc(f);
  if (r >= 9223372036854775808.0) return INT64_MAX;
  if (r < -9223372036854775808.0) return INT64_MIN;
  return static_cast<int64_t>(r);
}

// Round half away from zero, saturated to u64; NaN and negatives -> 0 (F2U).
inline uint64_t roundToU64(double f) {
  if (f != f) return 0;
  double r = std::round(f);
  if (r <= 0.0) return 0;
  if (r >= 18446744073709551616.0) return UINT64_MAX;
  return static_cast<uint64_t>(r);
}

}  // namespace virtcom::vm
