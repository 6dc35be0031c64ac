#pragma once
// The units of a duration: one table for IEC time literals (T#1h2m3s), the printer of TIME and
// LTIME values, the CLI's duration options (--cycle 10ms) and cell-file quantities ("150 ms").
#include <cstdint>
#include <string_view>

#include "core/ascii.hpp"

namespace virtcom {

struct DurationUnit {
  std::string_view iec;       // IEC 61131-3 symbol, matched in any case: d, h, m, s, ms, us, ns
  std::string_view quantity;  // symbol in cell-file quantities, exact case; empty where there is
                              // none (there `m` means metres and minutes are `min`)
  uint64_t ns;
};

// Largest first, the order in which the printer writes them.
inline constexpr DurationUnit kDurationUnits[] = {
    {"d", "", 86'400'000'000'000},  {"h", "h", 3'600'000'000'000}, {"m", "min", 60'000'000'000},
    {"s", "s", 1'000'000'000},      {"ms", "ms", 1'000'000},       {"us", "us", 1'000},
    {"ns", "ns", 1},
};

// The unit whose IEC symbol is `symbol` in any case (`MS`, `ms`); null if none.
constexpr const DurationUnit* iecDurationUnit(std::string_view symbol) {
  for (const DurationUnit& unit : kDurationUnits)
    if (iequalsAscii(unit.iec, symbol)) return &unit;
  return nullptr;
}

// The unit whose IEC symbol begins `text` (any case), the longest if several (`ms`, not `m`, in
// `ms5`); null if none. For readers that take units from a run of text without delimiters.
constexpr const DurationUnit* iecDurationUnitAtStart(std::string_view text) {
  const DurationUnit* longest = nullptr;
  for (const DurationUnit& unit : kDurationUnits)
    if (istartsWithAscii(text, unit.iec) && (longest == nullptr || unit.iec.size() > longest->iec.size()))
      longest = &unit;
  return longest;
}

// The unit whose cell-file symbol is exactly `symbol` (`min`, `ms`); null if none.
constexpr const DurationUnit* quantityDurationUnit(std::string_view symbol) {
  for (const DurationUnit& unit : kDurationUnits)
    if (!unit.quantity.empty() && unit.quantity == symbol) return &unit;
  return nullptr;
}

}  // namespace virtcom
