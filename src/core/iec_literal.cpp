#include "core/iec_literal.hpp"

#include <cmath>
#include <limits>

#include "core/iec_value.hpp"

namespace virtcom {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
char toUpper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (toUpper(a[i]) != toUpper(b[i])) return false;
  return true;
}

bool fail(LiteralError& why, const char* what, std::string_view quoted = {}) {
  why = {what, quoted};
  return false;
}

struct DurationUnit {
  std::string_view name;
  uint64_t ns;
};
constexpr DurationUnit kDurationUnits[] = {
    {"d", 86'400'000'000'000ull}, {"h", 3'600'000'000'000ull}, {"m", 60'000'000'000ull},
    {"s", 1'000'000'000ull},      {"ms", 1'000'000ull},        {"us", 1'000ull},
    {"ns", 1ull},
};

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
  if (i >= body.size()) return fail(why, "no value");
  while (i < body.size()) {
    size_t numStart = i;
    while (i < body.size() && (isDigit(body[i]) || body[i] == '_')) ++i;
    uint64_t whole = 0;
    if (!parseDecimal(body.substr(numStart, i - numStart), whole)) return fail(why, "expected a number");
    std::string_view fraction;
    if (i < body.size() && body[i] == '.') {
      size_t fracStart = ++i;
      while (i < body.size() && isDigit(body[i])) ++i;
      fraction = body.substr(fracStart, i - fracStart);
    }
    size_t unitStart = i;
    while (i < body.size() && isAlpha(body[i])) ++i;
    std::string_view unitName = body.substr(unitStart, i - unitStart);
    const DurationUnit* unit = nullptr;
    for (const DurationUnit& u : kDurationUnits)
      if (equalsNoCase(u.name, unitName)) unit = &u;
    if (unit == nullptr && unitName.empty()) return fail(why, "missing unit (d, h, m, s, ms, us, ns)");
    if (unit == nullptr) return fail(why, "unknown unit", unitName);
    uint64_t part = 0;
    if (__builtin_mul_overflow(whole, unit->ns, &part)) return fail(why, "value too large");
    if (!fraction.empty()) {
      long double frac = 0, scale = 1;
      for (char c : fraction.substr(0, 18)) frac += (c - '0') * (scale /= 10);
      uint64_t fracNs = static_cast<uint64_t>(std::llround(frac * static_cast<long double>(unit->ns)));
      if (__builtin_add_overflow(part, fracNs, &part)) return fail(why, "value too large");
    }
    if (__builtin_add_overflow(ns, part, &ns)) return fail(why, "value too large");
    while (i < body.size() && body[i] == '_') ++i;
  }
  if (ns > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) return fail(why, "value too large");
  return true;
}

bool decodeDate(std::string_view body, int64_t& seconds, LiteralError& why) {
  std::string_view parts[3];
  uint64_t y = 0, m = 0, d = 0;
  if (splitParts(body, '-', parts, 3) != 3 || !parseDecimal(parts[0], y) || !parseDecimal(parts[1], m) ||
      !parseDecimal(parts[2], d))
    return fail(why, "expected yyyy-mm-dd");
  static constexpr unsigned kDaysInMonth[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  if (y < 1970 || y > 9999 || m < 1 || m > 12 || d < 1 || d > kDaysInMonth[m - 1] || (m == 2 && d == 29 && !leap))
    return fail(why, "no such date");
  seconds = daysFromCivil(static_cast<int64_t>(y), static_cast<unsigned>(m), static_cast<unsigned>(d)) * 86400;
  return true;
}

// hh:mm[:ss[.fff]] to milliseconds since midnight.
bool decodeTimeOfDay(std::string_view body, int64_t& ms, LiteralError& why) {
  std::string_view parts[3];
  size_t n = splitParts(body, ':', parts, 3);
  uint64_t h = 0, m = 0, s = 0, fracMs = 0;
  if (n < 2 || n > 3 || !parseDecimal(parts[0], h) || !parseDecimal(parts[1], m)) return fail(why, "expected hh:mm:ss");
  if (n == 3) {
    std::string_view secPart = parts[2];
    size_t dot = secPart.find('.');
    if (!parseDecimal(secPart.substr(0, dot), s)) return fail(why, "expected hh:mm:ss");
    if (dot != std::string_view::npos) {
      std::string_view frac = secPart.substr(dot + 1);
      uint64_t scale = 100;
      for (char c : frac) {
        if (!isDigit(c)) return fail(why, "malformed fraction of a second");
        fracMs += static_cast<uint64_t>(c - '0') * scale;
        scale /= 10;
      }
    }
  }
  if (h > 23 || m > 59 || s > 59) return fail(why, "no such time of day");
  ms = static_cast<int64_t>(((h * 60 + m) * 60 + s) * 1000 + fracMs);
  return true;
}

// yyyy-mm-dd-hh:mm:ss[.f] to seconds since 1970 (the fraction is dropped: DT counts seconds).
bool decodeDateAndTime(std::string_view body, int64_t& seconds, LiteralError& why) {
  size_t dash = std::string_view::npos, count = 0;
  for (size_t i = 0; i < body.size() && count < 3; ++i)
    if (body[i] == '-' && ++count == 3) dash = i;
  if (dash == std::string_view::npos) return fail(why, "expected yyyy-mm-dd-hh:mm:ss");
  int64_t daySeconds = 0, ms = 0;
  if (!decodeDate(body.substr(0, dash), daySeconds, why) || !decodeTimeOfDay(body.substr(dash + 1), ms, why))
    return false;
  seconds = daySeconds + ms / 1000;
  return true;
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
      {"DATE_AND_TIME", LiteralFamily::Dt},
  };
  for (const Entry& e : kEntries)
    if (equalsNoCase(e.prefix, prefix)) return e.family;
  return LiteralFamily::None;
}

bool parseDecimal(std::string_view digits, uint64_t& out) {
  out = 0;
  bool any = false;
  for (char c : digits) {
    if (c == '_') continue;
    if (!isDigit(c)) return false;
    if (__builtin_mul_overflow(out, 10u, &out) || __builtin_add_overflow(out, uint64_t(c - '0'), &out))
      return false;
    any = true;
  }
  return any;
}

namespace {

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

// Date bodies may contain underscores in literals; run-time text has none to drop, so a body
// with one is simply malformed.
bool decodeFamily(std::string_view body, LiteralFamily family, int64_t& value) {
  LiteralError why;
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
    case LiteralFamily::None: break;
  }
  return false;
}

}  // namespace

bool parseTimeOrDateText(std::string_view text, LiteralFamily family, int64_t& value) {
  text = trimmed(text);
  size_t hash = text.find('#');
  if (hash != std::string_view::npos) {
    if (literalFamily(text.substr(0, hash)) != family) return false;
    text.remove_prefix(hash + 1);
  }
  return decodeFamily(text, family, value);
}

bool parseIntegerText(std::string_view text, int64_t& value) {
  text = trimmed(text);
  bool negative = false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  // A type prefix (INT#5, DINT#16#FF) says nothing about the value here.
  if (size_t hash = text.find('#'); hash != std::string_view::npos && hash > 0 && isAlpha(text[0]))
    text.remove_prefix(hash + 1);
  uint64_t base = 10;
  if (size_t hash = text.find('#'); hash != std::string_view::npos && hash > 0) {
    uint64_t b = 0;
    if (parseDecimal(text.substr(0, hash), b) && (b == 2 || b == 8 || b == 16)) {
      base = b;
      text.remove_prefix(hash + 1);
    }
  }
  const uint64_t limit = negative ? uint64_t{1} << 63 : (uint64_t{1} << 63) - 1;
  uint64_t magnitude = 0;
  bool any = false;
  for (char c : text) {
    if (c == '_' && any) continue;
    uint64_t digit = isDigit(c) ? static_cast<uint64_t>(c - '0')
                     : isAlpha(c) ? static_cast<uint64_t>(toUpper(c) - 'A' + 10)
                                  : base;
    if (digit >= base) break;
    magnitude = magnitude > (limit - digit) / base ? limit : magnitude * base + digit;
    any = true;
  }
  if (!any) return false;
  value = negative ? static_cast<int64_t>(0 - magnitude) : static_cast<int64_t>(magnitude);
  return true;
}

}  // namespace virtcom
