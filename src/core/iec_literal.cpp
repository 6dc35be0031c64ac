#include "core/iec_literal.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "core/ascii.hpp"
#include "core/duration_units.hpp"
#include "core/iec_value.hpp"

namespace virtcom {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

bool fail(LiteralError& why, const char* what, std::string_view quoted = {}) {
  why = {LiteralError::Kind::Malformed, what, quoted};
  return false;
}

bool failEmpty(LiteralError& why) {
  why = {LiteralError::Kind::Empty, "no value", {}};
  return false;
}

bool failTooLarge(LiteralError& why) {
  why = {LiteralError::Kind::TooLarge, "value too large", {}};
  return false;
}

// "missing unit (d, h, m, s, ms, us, ns)", listing kDurationUnits so the message cannot go stale.
constexpr std::string_view kMissingUnitHead = "missing unit (";
constexpr size_t missingUnitLength() {
  size_t n = kMissingUnitHead.size() + 1;  // and ')'
  for (const DurationUnit& unit : kDurationUnits) n += unit.iec.size() + 2;
  return n - 2 + 1;  // no ", " after the last, a terminating NUL
}
constexpr auto kMissingUnit = [] {
  std::array<char, missingUnitLength()> text{};
  size_t at = 0;
  auto append = [&](std::string_view part) {
    for (char c : part) text[at++] = c;
  };
  append(kMissingUnitHead);
  for (const DurationUnit& unit : kDurationUnits) {
    if (&unit != kDurationUnits) append(", ");
    append(unit.iec);
  }
  append(")");
  return text;
}();

// Splits `s` at `sep` into at most `maxParts` pieces.
size_t splitParts(std::string_view s, char sep, std::string_view* parts, size_t maxParts) {
  size_t count = 0;
  while (count < maxParts) {
    size_t at = s.find(sep);
    parts[count++] = s.substr(0, at);
    if (at == std::string_view::npos) return count;
    s.remove_prefix(at + 1);
  }
  return maxParts + 1;  // too many separators
}

}  // namespace

// Decodes what follows `T#`: an optional sign, then groups of number and unit such as
// `1h2m3s4ms`, `1.5s` or `1_000ms`. The magnitude must fit in int64 nanoseconds.
bool decodeDuration(std::string_view body, uint64_t& ns, bool& negative, LiteralError& why) {
  ns = 0;
  negative = false;
  size_t i = 0;
  if (i < body.size() && (body[i] == '-' || body[i] == '+')) negative = body[i++] == '-';
  if (i >= body.size()) return failEmpty(why);
  while (i < body.size()) {
    size_t numStart = i;
    while (i < body.size() && (isAsciiDigit(body[i]) || body[i] == '_')) ++i;
    uint64_t whole = 0;
    if (!parseDecimal(body.substr(numStart, i - numStart), whole)) return fail(why, "expected a number");
    std::string_view fraction;
    if (i < body.size() && body[i] == '.') {
      size_t fracStart = ++i;
      while (i < body.size() && isAsciiDigit(body[i])) ++i;
      fraction = body.substr(fracStart, i - fracStart);
    }
    size_t unitStart = i;
    while (i < body.size() && isAsciiLetter(body[i])) ++i;
    std::string_view unitName = body.substr(unitStart, i - unitStart);
    const DurationUnit* unit = iecDurationUnit(unitName);
    if (unit == nullptr && unitName.empty()) return fail(why, kMissingUnit.data());
    if (unit == nullptr) return fail(why, "unknown unit", unitName);
    uint64_t part = 0;
    if (__builtin_mul_overflow(whole, unit->ns, &part)) return failTooLarge(why);
    if (!fraction.empty()) {
      long double frac = 0, scale = 1;
      for (char c : fraction.substr(0, 18)) frac += (c - '0') * (scale /= 10);
      uint64_t fracNs = static_cast<uint64_t>(std::llround(frac * static_cast<long double>(unit->ns)));
      if (__builtin_add_overflow(part, fracNs, &part)) return failTooLarge(why);
    }
    if (__builtin_add_overflow(ns, part, &ns)) return failTooLarge(why);
    while (i < body.size() && body[i] == '_') ++i;
  }
  if (ns > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) return failTooLarge(why);
  return true;
}

namespace {

// The first year of the 64-bit nanosecond dates (LDATE, LDT): LDT#1677-09-21-00:12:43.145224192.
constexpr uint64_t kFirstLongYear = 1677;

// yyyy-mm-dd from `firstYear` to 9999, to seconds since 1970 (negative before 1970).
bool decodeCivilDate(std::string_view body, uint64_t firstYear, int64_t& seconds, LiteralError& why) {
  std::string_view parts[3];
  uint64_t y = 0, m = 0, d = 0;
  if (splitParts(body, '-', parts, 3) != 3 || !parseDecimal(parts[0], y) || !parseDecimal(parts[1], m) ||
      !parseDecimal(parts[2], d))
    return fail(why, "expected yyyy-mm-dd");
  static constexpr unsigned kDaysInMonth[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  if (y > 9999 || m < 1 || m > 12 || d < 1 || d > kDaysInMonth[m - 1] || (m == 2 && d == 29 && !leap))
    return fail(why, "no such date");
  if (y < firstYear)
    return fail(why, firstYear == 1970 ? "before 1970: DATE and DT count unsigned seconds since 1970 (LDATE and LDT "
                                         "reach back to 1677)"
                                       : "before 1677: LDATE and LDT count signed 64-bit nanoseconds since 1970");
  seconds = daysFromCivil(static_cast<int64_t>(y), static_cast<unsigned>(m), static_cast<unsigned>(d)) * 86400;
  return true;
}

// 64-bit nanoseconds since 1970 reach from September 1677 to April 2262.
bool failOutsideLdt(LiteralError& why, bool before) {
  why = {LiteralError::Kind::TooLarge,
         before ? "before LDT#1677-09-21-00:12:43.145224192, the first of 64-bit nanoseconds"
                : "beyond LDT#2262-04-11-23:47:16.854775807, the last of 64-bit nanoseconds",
         {}};
  return false;
}

// hh:mm[:ss[.fffffffff]] to nanoseconds since midnight (digits beyond 1 ns are ignored).
bool decodeClockNs(std::string_view body, int64_t& ns, LiteralError& why) {
  std::string_view parts[3];
  size_t n = splitParts(body, ':', parts, 3);
  uint64_t h = 0, m = 0, s = 0, fracNs = 0;
  if (n < 2 || n > 3 || !parseDecimal(parts[0], h) || !parseDecimal(parts[1], m)) return fail(why, "expected hh:mm:ss");
  if (n == 3) {
    std::string_view secPart = parts[2];
    size_t dot = secPart.find('.');
    if (!parseDecimal(secPart.substr(0, dot), s)) return fail(why, "expected hh:mm:ss");
    if (dot != std::string_view::npos) {
      std::string_view frac = secPart.substr(dot + 1);
      uint64_t scale = 100'000'000;
      for (char c : frac) {
        if (!isAsciiDigit(c)) return fail(why, "malformed fraction of a second");
        fracNs += static_cast<uint64_t>(c - '0') * scale;
        scale /= 10;
      }
    }
  }
  if (h > 23 || m > 59 || s > 59) return fail(why, "no such time of day");
  ns = static_cast<int64_t>(((h * 60 + m) * 60 + s) * 1'000'000'000 + fracNs);
  return true;
}

// yyyy-mm-dd-hh:mm:ss[.f] from `firstYear` on to nanoseconds since 1970.
bool decodeDateAndTimeNs(std::string_view body, uint64_t firstYear, int64_t& ns, LiteralError& why) {
  size_t dash = std::string_view::npos, count = 0;
  for (size_t i = 0; i < body.size() && count < 3; ++i)
    if (body[i] == '-' && ++count == 3) dash = i;
  if (dash == std::string_view::npos) return fail(why, "expected yyyy-mm-dd-hh:mm:ss");
  int64_t daySeconds = 0, clock = 0;
  if (!decodeCivilDate(body.substr(0, dash), firstYear, daySeconds, why) ||
      !decodeClockNs(body.substr(dash + 1), clock, why))
    return false;
  const __int128 wide = static_cast<__int128>(daySeconds) * 1'000'000'000 + clock;
  if (wide < std::numeric_limits<int64_t>::min()) return failOutsideLdt(why, true);
  if (wide > std::numeric_limits<int64_t>::max()) return failOutsideLdt(why, false);
  ns = static_cast<int64_t>(wide);
  return true;
}

}  // namespace

bool decodeDate(std::string_view body, int64_t& seconds, LiteralError& why) {
  return decodeCivilDate(body, 1970, seconds, why);
}

// hh:mm[:ss[.fff]] to milliseconds since midnight.
bool decodeTimeOfDay(std::string_view body, int64_t& ms, LiteralError& why) {
  int64_t ns = 0;
  if (!decodeClockNs(body, ns, why)) return false;
  ms = ns / 1'000'000;
  return true;
}

// yyyy-mm-dd-hh:mm:ss[.f] to seconds since 1970 (the fraction is dropped: DT counts seconds).
bool decodeDateAndTime(std::string_view body, int64_t& seconds, LiteralError& why) {
  int64_t ns = 0;
  if (!decodeDateAndTimeNs(body, 1970, ns, why)) return false;
  seconds = ns / 1'000'000'000;
  return true;
}

bool decodeLiteralBody(std::string_view body, LiteralFamily family, int64_t& value, LiteralError& why) {
  switch (family) {
    case LiteralFamily::Time:
    case LiteralFamily::Ltime: {
      uint64_t ns = 0;
      bool negative = false;
      if (!decodeDuration(body, ns, negative, why)) return false;
      int64_t magnitude = static_cast<int64_t>(family == LiteralFamily::Time ? ns / 1000000 : ns);
      value = negative ? -magnitude : magnitude;
      return true;
    }
    case LiteralFamily::Date: return decodeDate(body, value, why);
    case LiteralFamily::Tod: return decodeTimeOfDay(body, value, why);
    case LiteralFamily::Dt: return decodeDateAndTime(body, value, why);
    case LiteralFamily::Ldate: {
      int64_t seconds = 0;
      if (!decodeCivilDate(body, kFirstLongYear, seconds, why)) return false;
      if (__builtin_mul_overflow(seconds, int64_t{1'000'000'000}, &value)) return failOutsideLdt(why, seconds < 0);
      return true;
    }
    case LiteralFamily::Ltod: return decodeClockNs(body, value, why);
    case LiteralFamily::Ldt: return decodeDateAndTimeNs(body, kFirstLongYear, value, why);
    case LiteralFamily::None: break;
  }
  return fail(why, "not a time or date literal");
}

LiteralFamily literalFamily(std::string_view prefix) {
  struct Entry {
    std::string_view prefix;
    LiteralFamily family;
  };
  static constexpr Entry kEntries[] = {
      {"T", LiteralFamily::Time},  {"TIME", LiteralFamily::Time},         {"LT", LiteralFamily::Ltime},
      {"LTIME", LiteralFamily::Ltime}, {"D", LiteralFamily::Date},         {"DATE", LiteralFamily::Date},
      {"TOD", LiteralFamily::Tod}, {"TIME_OF_DAY", LiteralFamily::Tod},   {"DT", LiteralFamily::Dt},
      {"DATE_AND_TIME", LiteralFamily::Dt}, {"LDATE", LiteralFamily::Ldate}, {"LD", LiteralFamily::Ldate},
      {"LTOD", LiteralFamily::Ltod}, {"LTIME_OF_DAY", LiteralFamily::Ltod}, {"LDT", LiteralFamily::Ldt},
      {"LDATE_AND_TIME", LiteralFamily::Ldt},
  };
  for (const Entry& e : kEntries)
    if (iequalsAscii(e.prefix, prefix)) return e.family;
  return LiteralFamily::None;
}

bool parseDigits(std::string_view digits, unsigned base, uint64_t& out) {
  out = 0;
  bool any = false;
  for (char c : digits) {
    if (c == '_') continue;
    const int digit = asciiDigitValue(c);
    if (digit < 0 || static_cast<unsigned>(digit) >= base) return false;
    if (__builtin_mul_overflow(out, uint64_t{base}, &out) || __builtin_add_overflow(out, uint64_t(digit), &out))
      return false;
    any = true;
  }
  return any;
}

bool parseDecimal(std::string_view digits, uint64_t& out) { return parseDigits(digits, 10, out); }

bool parseRadix(std::string_view text, unsigned& base) {
  uint64_t value = 0;
  if (!parseDecimal(text, value) || (value != 2 && value != 8 && value != 16)) return false;
  base = static_cast<unsigned>(value);
  return true;
}

// Date bodies may contain underscores in literals; run-time text has none to drop, so a body
// with one is simply malformed.
bool parseTimeOrDateText(std::string_view text, LiteralFamily family, int64_t& value) {
  text = trimmed(text);
  size_t hash = text.find('#');
  if (hash != std::string_view::npos) {
    if (literalFamily(text.substr(0, hash)) != family) return false;
    text.remove_prefix(hash + 1);
  }
  LiteralError why;
  return decodeLiteralBody(text, family, value, why);
}

bool parseIntegerText(std::string_view text, int64_t& value) {
  text = trimmed(text);
  bool negative = false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  // A type prefix (INT#5, DINT#16#FF) says nothing about the value here.
  if (size_t hash = text.find('#'); hash != std::string_view::npos && hash > 0 && isAsciiLetter(text[0]))
    text.remove_prefix(hash + 1);
  unsigned base = 10;
  if (size_t hash = text.find('#'); hash != std::string_view::npos && hash > 0 && parseRadix(text.substr(0, hash), base))
    text.remove_prefix(hash + 1);
  const uint64_t limit = negative ? uint64_t{1} << 63 : (uint64_t{1} << 63) - 1;
  uint64_t magnitude = 0;
  bool any = false;
  for (char c : text) {
    if (c == '_' && any) continue;
    const int digitOrNone = asciiDigitValue(c);
    if (digitOrNone < 0 || static_cast<unsigned>(digitOrNone) >= base) break;
    const uint64_t digit = static_cast<uint64_t>(digitOrNone);
    magnitude = magnitude > (limit - digit) / base ? limit : magnitude * base + digit;
    any = true;
  }
  if (!any) return false;
  value = negative ? static_cast<int64_t>(0 - magnitude) : static_cast<int64_t>(magnitude);
  return true;
}

}  // namespace virtcom
