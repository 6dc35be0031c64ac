#pragma once
// Conversions between engineering values and telegram raw numbers (docs/drives.md, Units).
// Real -> integer rounds to nearest, ties to even (S7 ROUND / Logix REAL->INT), then saturates
// to the word's range. Pure functions, no allocation.
#include <cmath>
#include <cstdint>

namespace virtcom::drives {

inline constexpr double kN2Full = 16384.0;        // 0x4000 = 100 %
inline constexpr double kN4Full = 1073741824.0;   // 0x40000000 = 100 %

// Round half to even, saturated to [lo, hi].
inline int64_t roundSaturate(double v, int64_t lo, int64_t hi) {
  if (std::isnan(v)) return 0;
  const double r = std::nearbyint(v);  // default rounding mode: to nearest, ties to even
  if (r <= static_cast<double>(lo)) return lo;
  if (r >= static_cast<double>(hi)) return hi;
  return static_cast<int64_t>(r);
}
inline int16_t toInt16(double v) { return static_cast<int16_t>(roundSaturate(v, INT16_MIN, INT16_MAX)); }
inline int32_t toInt32(double v) { return static_cast<int32_t>(roundSaturate(v, INT32_MIN, INT32_MAX)); }

// N2 / N4 speed normalisation against the reference speed p2000 (rpm).
inline int16_t n2FromRpm(double rpm, double refRpm) { return toInt16(rpm * kN2Full / refRpm); }
inline double rpmFromN2(int64_t raw, double refRpm) { return static_cast<double>(raw) * refRpm / kN2Full; }
inline int32_t n4FromRpm(double rpm, double refRpm) { return toInt32(rpm * kN4Full / refRpm); }
inline double rpmFromN4(int64_t raw, double refRpm) { return static_cast<double>(raw) * refRpm / kN4Full; }

// Percent words (OVERRIDE, MDI_ACC, MDI_DEC, current, torque): 0x4000 = 100 %.
inline int16_t q14FromPercent(double percent) { return toInt16(percent * kN2Full / 100.0); }
inline double percentFromQ14(int64_t raw) { return static_cast<double>(raw) * 100.0 / kN2Full; }

// Frequency in 0.01 Hz; 1 Hz = 60 rpm / pole pairs (the thesis assumes one pole pair).
inline double rpmFromCentiHz(int64_t centiHz, int polePairs) { return static_cast<double>(centiHz) * 0.6 / polePairs; }
inline int16_t centiHzFromRpm(double rpm, int polePairs) { return toInt16(rpm * polePairs / 0.6); }

}  // namespace virtcom::drives
