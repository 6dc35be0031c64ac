// writeValueFromText: parses an IEC literal for an elementary, string or enum variable and
// stores it little endian. A small self-contained parser (no dependency on src/lang).
// Accepted: 42, -7, 16#FF, 2#1010, 8#17, 1_000, INT#5; 1.5, 1E3, -2.5e-3; TRUE/FALSE/1/0;
// T#1s500ms, TIME#-2m, LTIME#5ns, LT#1.5us, a plain integer (TIME: ms, LTIME: ns);
// D#2024-01-02, TOD#12:30:00.5, DT#2024-01-02-12:30:00 or the raw number;
// 'text' with $-escapes or bare text (STRING, truncated to the capacity); "text" for WSTRING;
// Color#Red, Red or a number for enums. Read-only flags are not checked here (the caller's job).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "bytecode/module.hpp"

namespace virtcom::bc {

namespace {

using Error = std::string;

char upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }

bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Removes a leading "NAME#" when NAME is one of `names` (case-insensitive). True if removed.
bool stripPrefix(std::string_view& s, std::initializer_list<std::string_view> names) {
  const size_t hash = s.find('#');
  if (hash == std::string_view::npos) return false;
  for (std::string_view n : names) {
    if (equalsNoCase(s.substr(0, hash), n)) {
      s.remove_prefix(hash + 1);
      return true;
    }
  }
  return false;
}

// Removes a leading "IDENT#" whose IDENT starts with a letter (a type name, not a base).
void stripTypeName(std::string_view& s) {
  const size_t hash = s.find('#');
  if (hash == std::string_view::npos || hash == 0 || !std::isalpha(static_cast<unsigned char>(s[0]))) return;
  for (size_t i = 0; i < hash; ++i)
    if (!std::isalnum(static_cast<unsigned char>(s[i])) && s[i] != '_') return;
  s.remove_prefix(hash + 1);
}

void storeLe(uint8_t* p, uint64_t v, uint32_t size) {
  for (uint32_t i = 0; i < size; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

int digitValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'z') return c - 'a' + 10;
  if (c >= 'A' && c <= 'Z') return c - 'A' + 10;
  return 99;
}

// Digits in `base` with single '_' separators; false on anything else or on u64 overflow.
bool parseDigits(std::string_view s, unsigned base, uint64_t& out) {
  if (s.empty() || s.front() == '_' || s.back() == '_') return false;
  out = 0;
  for (char c : s) {
    if (c == '_') continue;
    const int d = digitValue(c);
    if (d >= static_cast<int>(base)) return false;
    if (__builtin_mul_overflow(out, uint64_t{base}, &out) ||
        __builtin_add_overflow(out, static_cast<uint64_t>(d), &out))
      return false;
  }
  return true;
}

// An integer literal: [sign] [base#] digits. Sets magnitude and sign.
Error parseInteger(std::string_view s, bool& negative, uint64_t& magnitude) {
  negative = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  unsigned base = 10;
  const size_t hash = s.find('#');
  if (hash != std::string_view::npos) {
    const std::string_view b = s.substr(0, hash);
    if (b == "16") base = 16;
    else if (b == "8") base = 8;
    else if (b == "2") base = 2;
    else return "invalid integer base '" + std::string(b) + "'";
    s.remove_prefix(hash + 1);
  }
  if (!parseDigits(s, base, magnitude)) return "not an integer";
  return {};
}

std::string rangeError(bool negative, uint64_t magnitude, std::string_view typeName, bool isSigned, unsigned bits) {
  std::string lo = isSigned ? "-" + std::to_string(bits == 64 ? uint64_t{1} << 63 : uint64_t{1} << (bits - 1)) : "0";
  const uint64_t max = isSigned ? (uint64_t{1} << (bits - 1)) - 1 : bits == 64 ? UINT64_MAX : (uint64_t{1} << bits) - 1;
  return "value " + std::string(negative && magnitude ? "-" : "") + std::to_string(magnitude) +
         " out of range for " + std::string(typeName) + " (" + lo + ".." + std::to_string(max) + ")";
}

// Parses an integer for a type of `bits` width and checks the range; out is the two's
// complement bit pattern.
Error parseRangedInteger(std::string_view s, std::string_view typeName, bool isSigned, unsigned bits, uint64_t& out) {
  bool negative = false;
  uint64_t mag = 0;
  if (Error e = parseInteger(s, negative, mag); !e.empty())
    return "invalid " + std::string(typeName) + " literal '" + std::string(s) + "'";
  if (isSigned) {
    const uint64_t maxPos = (uint64_t{1} << (bits - 1)) - 1;
    if ((!negative && mag > maxPos) || (negative && mag > maxPos + 1))
      return rangeError(negative, mag, typeName, true, bits);
    out = negative ? 0 - mag : mag;
  } else {
    const uint64_t max = bits == 64 ? UINT64_MAX : (uint64_t{1} << bits) - 1;
    if ((negative && mag != 0) || mag > max) return rangeError(negative, mag, typeName, false, bits);
    out = mag;
  }
  return {};
}

Error writeBool(std::string_view s, bool& out) {
  stripPrefix(s, {"BOOL"});
  if (equalsNoCase(s, "TRUE") || s == "1") out = true;
  else if (equalsNoCase(s, "FALSE") || s == "0") out = false;
  else return "invalid BOOL literal '" + std::string(s) + "' (expected TRUE, FALSE, 1 or 0)";
  return {};
}

Error parseFloat(std::string_view s, double& out) {
  stripPrefix(s, {"REAL", "LREAL"});
  std::string clean;
  for (char c : s)
    if (c != '_') clean += c;
  const char* first = clean.data();
  if (!clean.empty() && clean.front() == '+') ++first;
  auto res = std::from_chars(first, clean.data() + clean.size(), out, std::chars_format::general);
  if (clean.empty() || res.ec != std::errc() || res.ptr != clean.data() + clean.size())
    return "invalid real literal '" + std::string(s) + "'";
  return {};
}

// "1d2h3m4s5ms6us7ns" with optional fractions ("1.5s") and underscores; result in ns.
Error parseDurationNs(std::string_view s, int64_t& out) {
  bool negative = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s.empty()) return "empty duration";
  static constexpr struct { std::string_view suffix; uint64_t ns; } kUnits[] = {
      {"ms", 1'000'000}, {"us", 1'000}, {"ns", 1}, {"d", 86'400'000'000'000},
      {"h", 3'600'000'000'000}, {"m", 60'000'000'000}, {"s", 1'000'000'000}};
  uint64_t total = 0;
  while (!s.empty()) {
    size_t n = 0;
    while (n < s.size() && (std::isdigit(static_cast<unsigned char>(s[n])) || s[n] == '_' || s[n] == '.')) ++n;
    const std::string_view number = s.substr(0, n);
    s.remove_prefix(n);
    if (!s.empty() && s.front() == '_') s.remove_prefix(1);
    const auto* unit = std::find_if(std::begin(kUnits), std::end(kUnits), [&](const auto& u) {
      return s.size() >= u.suffix.size() && equalsNoCase(s.substr(0, u.suffix.size()), u.suffix);
    });
    if (number.empty() || unit == std::end(kUnits)) return "invalid duration";
    s.remove_prefix(unit->suffix.size());
    if (!s.empty() && s.front() == '_') s.remove_prefix(1);
    const size_t dot = number.find('.');
    uint64_t whole = 0, part = 0;
    if (!parseDigits(number.substr(0, dot), 10, whole)) return "invalid duration";
    if (dot != std::string_view::npos) {
      const std::string_view frac = number.substr(dot + 1);
      double f = 0.0;
      if (!frac.empty() && frac.find('.') == std::string_view::npos) {
        std::string t = "0." + std::string(frac);
        std::from_chars(t.data(), t.data() + t.size(), f);
      } else {
        return "invalid duration";
      }
      part = static_cast<uint64_t>(std::llround(f * static_cast<double>(unit->ns)));
    }
    if (__builtin_mul_overflow(whole, unit->ns, &whole) || __builtin_add_overflow(total, whole, &total) ||
        __builtin_add_overflow(total, part, &total) || total > uint64_t{INT64_MAX})
      return "duration out of range";
  }
  out = negative ? -static_cast<int64_t>(total) : static_cast<int64_t>(total);
  return {};
}

Error parseTime(std::string_view s, ElemType t, int64_t& out) {
  const bool isLtime = t == ElemType::Ltime;
  const bool prefixed = isLtime ? stripPrefix(s, {"LTIME", "LT"}) : stripPrefix(s, {"TIME", "T"});
  if (!prefixed) {
    uint64_t raw = 0;
    if (Error e = parseRangedInteger(s, isLtime ? "LTIME" : "TIME", true, isLtime ? 64 : 32, raw); !e.empty())
      return e;
    out = static_cast<int64_t>(raw);
    return {};
  }
  int64_t ns = 0;
  if (Error e = parseDurationNs(s, ns); !e.empty()) return e + " '" + std::string(s) + "'";
  out = isLtime ? ns : ns / 1'000'000;
  if (!isLtime && (out > INT32_MAX || out < INT32_MIN)) return "value out of range for TIME";
  return {};
}

// yyyy-mm-dd -> days since 1970.
bool parseDate(std::string_view& s, int64_t& days) {
  unsigned y = 0, mo = 0, d = 0;
  int n = 0;
  const std::string text(s);
  if (std::sscanf(text.c_str(), "%4u-%2u-%2u%n", &y, &mo, &d, &n) != 3) return false;
  if (mo < 1 || mo > 12 || d < 1 || d > 31) return false;
  days = daysFromCivil(y, mo, d);
  s.remove_prefix(static_cast<size_t>(n));
  return true;
}

// hh:mm[:ss[.fff]] -> ms since midnight.
bool parseClock(std::string_view s, int64_t& ms) {
  unsigned h = 0, mi = 0;
  double sec = 0.0;
  int n = 0;
  const std::string text(s);
  const int got = std::sscanf(text.c_str(), "%u:%u%n:%lf%n", &h, &mi, &n, &sec, &n);
  if (got < 2 || static_cast<size_t>(n) != text.size() || h > 23 || mi > 59 || sec < 0 || sec >= 60) return false;
  ms = (int64_t{h} * 3600 + mi * 60) * 1000 + std::llround(sec * 1000.0);
  return true;
}

Error parseDateLike(std::string_view s, ElemType t, uint64_t& out) {
  const std::string original(s);
  bool ok = false;
  int64_t v = 0;
  if (t == ElemType::Date && stripPrefix(s, {"DATE", "D"})) {
    int64_t days = 0;
    ok = parseDate(s, days) && s.empty();
    v = days * 86400;
  } else if (t == ElemType::Tod && stripPrefix(s, {"TIME_OF_DAY", "TOD"})) {
    ok = parseClock(s, v);
  } else if (t == ElemType::Dt && stripPrefix(s, {"DATE_AND_TIME", "DT"})) {
    int64_t days = 0, ms = 0;
    ok = parseDate(s, days) && !s.empty() && s.front() == '-';
    if (ok) {
      s.remove_prefix(1);
      ok = parseClock(s, ms);
    }
    v = days * 86400 + ms / 1000;
  } else {
    return parseRangedInteger(s, elemTypeInfo(t).name, false, 32, out);
  }
  if (!ok || v < 0 || v > UINT32_MAX)
    return "invalid " + std::string(elemTypeInfo(t).name) + " literal '" + original + "'";
  out = static_cast<uint64_t>(v);
  return {};
}

// The characters of a STRING literal: 'text' with $-escapes, or bare text taken as is.
Error unquote(std::string_view s, char quote, std::string& out) {
  if (s.size() < 2 || s.front() != quote || s.back() != quote) {
    out.assign(s);
    return {};
  }
  s = s.substr(1, s.size() - 2);
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '$') {
      out += s[i];
      continue;
    }
    if (++i >= s.size()) return "dangling '$' in string literal";
    switch (upper(s[i])) {
      case 'N': case 'L': out += '\n'; break;
      case 'R': out += '\r'; break;
      case 'T': out += '\t'; break;
      case 'P': out += '\f'; break;
      default: {
        const int hi = digitValue(s[i]), lo = i + 1 < s.size() ? digitValue(s[i + 1]) : 99;
        if (hi < 16 && lo < 16) {
          out += static_cast<char>(hi * 16 + lo);
          ++i;
        } else {
          out += s[i];  // $$, $', $"
        }
      }
    }
  }
  return {};
}

void writeString(const TypeDesc& t, const std::string& text, uint8_t* p) {
  const uint32_t cap = t.stringLength ? t.stringLength : (t.size ? t.size - 1 : 0);
  const size_t n = std::min<size_t>(text.size(), cap);
  std::memcpy(p, text.data(), n);
  std::memset(p + n, 0, cap + 1 - n);
}

// UTF-8 -> UTF-16LE units (invalid bytes are taken as Latin-1), truncated to the capacity.
void writeWstring(const TypeDesc& t, const std::string& text, uint8_t* p) {
  const uint32_t cap = t.stringLength ? t.stringLength : (t.size >= 2 ? t.size / 2 - 1 : 0);
  uint32_t n = 0;
  auto put = [&](uint32_t unit) {
    if (n < cap) storeLe(p + 2 * n++, unit, 2);
  };
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const int len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    uint32_t cp = c;
    if (len > 1 && i + len <= text.size()) {
      cp = c & (0x7f >> len);
      for (int k = 1; k < len; ++k) cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3f);
      i += len;
    } else {
      ++i;
    }
    if (cp >= 0x10000) {
      cp -= 0x10000;
      put(0xd800 + (cp >> 10));
      put(0xdc00 + (cp & 0x3ff));
    } else {
      put(cp);
    }
  }
  std::memset(p + 2 * n, 0, 2 * (cap + 1 - n));
}

Error writeElementary(const TypeDesc& t, std::string_view s, uint8_t* p) {
  const ElemTypeInfo& info = elemTypeInfo(t.elem);
  switch (info.kind) {
    case ElemKind::Bool: {
      bool b = false;
      if (Error e = writeBool(s, b); !e.empty()) return e;
      *p = b ? 1 : 0;
      return {};
    }
    case ElemKind::Bits:
    case ElemKind::Signed:
    case ElemKind::Unsigned: {
      stripTypeName(s);
      uint64_t v = 0;
      if (Error e = parseRangedInteger(s, info.name, info.kind == ElemKind::Signed, bitWidth(t.elem), v); !e.empty())
        return e;
      storeLe(p, v, info.sizeBytes);
      return {};
    }
    case ElemKind::Float: {
      double d = 0.0;
      if (Error e = parseFloat(s, d); !e.empty()) return e;
      if (t.elem == ElemType::Real) {
        const float f = static_cast<float>(d);
        std::memcpy(p, &f, 4);
      } else {
        std::memcpy(p, &d, 8);
      }
      return {};
    }
    case ElemKind::Duration: {
      int64_t v = 0;
      if (Error e = parseTime(s, t.elem, v); !e.empty()) return e;
      storeLe(p, static_cast<uint64_t>(v), info.sizeBytes);
      return {};
    }
    case ElemKind::Date: {
      uint64_t v = 0;
      if (Error e = parseDateLike(s, t.elem, v); !e.empty()) return e;
      storeLe(p, v, 4);
      return {};
    }
    case ElemKind::Text: break;
  }
  return "cannot write " + t.name + " from text";
}

Error writeEnum(const TypeDesc& t, std::string_view s, uint8_t* p) {
  const size_t hash = s.find('#');
  if (hash != std::string_view::npos && equalsNoCase(s.substr(0, hash), t.name)) s.remove_prefix(hash + 1);
  const uint32_t size = t.size ? t.size : elemTypeInfo(t.elem).sizeBytes;
  for (const Enumerator& e : t.enumerators) {
    if (equalsNoCase(e.name, s)) {
      storeLe(p, static_cast<uint64_t>(e.value), size);
      return {};
    }
  }
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s.front())) || s.front() == '-' || s.front() == '+'))
    return "'" + std::string(s) + "' is not a value of " + t.name;
  uint64_t v = 0;
  const ElemType base = isInteger(t.elem) ? t.elem : ElemType::Int;
  if (Error e = parseRangedInteger(s, t.name, isSignedInt(base), size * 8, v); !e.empty()) return e;
  storeLe(p, v, size);
  return {};
}

}  // namespace

std::string writeValueFromText(const Module& m, const VarRef& ref, std::string_view text, uint8_t* memory) {
  text = trim(text);
  if (ref.type >= m.types.size() && ref.bit < 0) return "unknown type";
  const uint32_t size = ref.bit >= 0 ? 1 : m.types[ref.type].size;
  if (ref.address < Module::kNullGuard || ref.address > m.memorySize() || size > m.memorySize() - ref.address)
    return "address outside memory";
  uint8_t* p = memory + ref.address;
  if (ref.bit >= 0) {
    bool b = false;
    if (Error e = writeBool(text, b); !e.empty()) return e;
    const auto mask = static_cast<uint8_t>(1u << (ref.bit & 7));
    *p = b ? (*p | mask) : (*p & ~mask);
    return {};
  }
  const TypeDesc& t = m.types[ref.type];
  switch (t.kind) {
    case TypeKind::Elementary:
      if (t.elem != ElemType::String && t.elem != ElemType::Wstring) return writeElementary(t, text, p);
      [[fallthrough]];
    case TypeKind::String: {
      std::string raw;
      const bool wide = t.elem == ElemType::Wstring;
      Error e = unquote(text, wide && !text.empty() && text.front() == '"' ? '"' : '\'', raw);
      if (!e.empty()) return e;
      if (wide) writeWstring(t, raw, p);
      else writeString(t, raw, p);
      return {};
    }
    case TypeKind::Enum: return writeEnum(t, text, p);
    default: return "cannot write a value of type " + t.name + " from text";
  }
}

}  // namespace virtcom::bc
