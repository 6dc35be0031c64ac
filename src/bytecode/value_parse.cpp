// writeValueFromText: parses an IEC literal for an elementary, string or enum variable and
// stores it little endian. Time and date bodies, their prefixes and integer digits are read by
// core/iec_literal, the reader the ST lexer uses; this file adds the type's range and storage.
// Accepted: 42, -7, 16#FF, 2#1010, 8#17, 1_000, INT#5; 1.5, 1E3, -2.5e-3; TRUE/FALSE/1/0;
// T#1s500ms, TIME#-2m, LTIME#5ns, LT#1.5us, a plain integer (TIME: ms, LTIME: ns);
// D#2024-01-02, TOD#12:30:00.5, DT#2024-01-02-12:30:00 or the raw number;
// 'text' with $-escapes or bare text (STRING, truncated to the capacity); "text" for WSTRING;
// Color#Red, Red or a number for enums. Read-only flags are not checked here (the caller's job).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>

#include "bytecode/module.hpp"
#include "core/ascii.hpp"
#include "core/iec_literal.hpp"

namespace virtcom::bc {

namespace {

using Error = std::string;

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
    if (iequalsAscii(s.substr(0, hash), n)) {
      s.remove_prefix(hash + 1);
      return true;
    }
  }
  return false;
}

// Removes a leading "NAME#" when NAME is a prefix of `family` (T#, LTIME#, TOD#, ...). True if removed.
bool stripFamilyPrefix(std::string_view& s, LiteralFamily family) {
  const size_t hash = s.find('#');
  if (hash == std::string_view::npos || literalFamily(s.substr(0, hash)) != family) return false;
  s.remove_prefix(hash + 1);
  return true;
}

// Removes a leading "IDENT#" whose IDENT starts with a letter (a type name, not a base).
void stripTypeName(std::string_view& s) {
  const size_t hash = s.find('#');
  if (hash == std::string_view::npos || hash == 0 || !isAsciiLetter(s[0])) return;
  for (size_t i = 0; i < hash; ++i)
    if (!isAsciiLetter(s[i]) && !isAsciiDigit(s[i]) && s[i] != '_') return;
  s.remove_prefix(hash + 1);
}

void storeLe(uint8_t* p, uint64_t v, uint32_t size) {
  for (uint32_t i = 0; i < size; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

// An integer literal: [sign] [base#] digits, underscores only between digits. Sets magnitude
// and sign; false if malformed or beyond 64 bits.
bool parseInteger(std::string_view s, bool& negative, uint64_t& magnitude) {
  negative = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  unsigned base = 10;
  if (const size_t hash = s.find('#'); hash != std::string_view::npos) {
    if (!parseRadix(s.substr(0, hash), base)) return false;
    s.remove_prefix(hash + 1);
  }
  return !s.empty() && s.front() != '_' && s.back() != '_' && parseDigits(s, base, magnitude);
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
  if (!parseInteger(s, negative, mag))
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
  if (iequalsAscii(s, "TRUE") || s == "1") out = true;
  else if (iequalsAscii(s, "FALSE") || s == "0") out = false;
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

// How this reader has always worded a refused duration.
const char* durationProblem(const LiteralError& why) {
  switch (why.kind) {
    case LiteralError::Kind::Empty: return "empty duration";
    case LiteralError::Kind::TooLarge: return "duration out of range";
    case LiteralError::Kind::Malformed: break;
  }
  return "invalid duration";
}

// T#1s500ms or LTIME#5ns (the body as core/iec_literal reads it), or a plain integer (TIME: ms, LTIME: ns).
Error parseTime(std::string_view s, ElemType t, int64_t& out) {
  const bool isLtime = t == ElemType::Ltime;
  if (!stripFamilyPrefix(s, isLtime ? LiteralFamily::Ltime : LiteralFamily::Time)) {
    uint64_t raw = 0;
    if (Error e = parseRangedInteger(s, isLtime ? "LTIME" : "TIME", true, isLtime ? 64 : 32, raw); !e.empty())
      return e;
    out = static_cast<int64_t>(raw);
    return {};
  }
  LiteralError why;
  if (!decodeLiteralBody(s, isLtime ? LiteralFamily::Ltime : LiteralFamily::Time, out, why))
    return durationProblem(why) + (" '" + std::string(s) + "'");
  if (!isLtime && (out > INT32_MAX || out < INT32_MIN)) return "value out of range for TIME";
  return {};
}

LiteralFamily dateFamily(ElemType t) {
  switch (t) {
    case ElemType::Date: return LiteralFamily::Date;
    case ElemType::Tod: return LiteralFamily::Tod;
    case ElemType::Ldate: return LiteralFamily::Ldate;
    case ElemType::Ltod: return LiteralFamily::Ltod;
    case ElemType::Ldt: return LiteralFamily::Ldt;
    default: return LiteralFamily::Dt;
  }
}

// D#2024-01-02, TOD#12:30:00.5, DT#2024-01-02-12:30:00, LDT#... (bodies as core/iec_literal
// reads them), or the raw number (32 bits, 64 for the long types).
Error parseDateLike(std::string_view s, ElemType t, uint64_t& out) {
  const std::string_view original = s;
  const LiteralFamily family = dateFamily(t);
  const bool isLong = elemTypeInfo(t).sizeBytes == 8;
  if (!stripFamilyPrefix(s, family)) return parseRangedInteger(s, elemTypeInfo(t).name, isLong, isLong ? 64 : 32, out);
  int64_t v = 0;
  LiteralError why;
  if (!decodeLiteralBody(s, family, v, why) || v < 0 || (!isLong && v > UINT32_MAX))
    return "invalid " + std::string(elemTypeInfo(t).name) + " literal '" + std::string(original) + "'";
  out = static_cast<uint64_t>(v);
  return {};
}

int hexDigitValue(char c) {
  const int digit = asciiDigitValue(c);
  return digit < 16 ? digit : -1;
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
    switch (asciiUpper(s[i])) {
      case 'N': case 'L': out += '\n'; break;
      case 'R': out += '\r'; break;
      case 'T': out += '\t'; break;
      case 'P': out += '\f'; break;
      default: {
        const int hi = hexDigitValue(s[i]), lo = i + 1 < s.size() ? hexDigitValue(s[i + 1]) : -1;
        if (hi >= 0 && lo >= 0) {
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

// CHAR from 'a' (or '$41'), WCHAR from "a" (or "$00E4"): exactly one character.
Error writeChar(ElemType t, std::string_view s, uint8_t* p) {
  const bool wide = t == ElemType::Wchar;
  std::string text;
  if (Error e = unquote(s, wide ? '"' : '\'', text); !e.empty()) return e;
  const std::string oneCharacter = wide ? "a WCHAR is one character, as \"a\"" : "a CHAR is one character, as 'a'";
  if (!wide) {
    if (text.size() != 1) return oneCharacter + ", found " + std::string(s);
    *p = static_cast<uint8_t>(text[0]);
    return {};
  }
  TypeDesc twoUnits;
  twoUnits.stringLength = 2;
  uint8_t units[6] = {};
  writeWstring(twoUnits, text, units);
  if (text.empty() || units[2] != 0 || units[3] != 0) return oneCharacter + ", found " + std::string(s);
  std::memcpy(p, units, 2);
  return {};
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
      storeLe(p, v, info.sizeBytes);
      return {};
    }
    case ElemKind::Char: return writeChar(t.elem, s, p);
    case ElemKind::Text: break;
  }
  return "cannot write " + t.name + " from text";
}

Error writeEnum(const TypeDesc& t, std::string_view s, uint8_t* p) {
  const size_t hash = s.find('#');
  if (hash != std::string_view::npos && iequalsAscii(s.substr(0, hash), t.name)) s.remove_prefix(hash + 1);
  const uint32_t size = t.size ? t.size : elemTypeInfo(t.elem).sizeBytes;
  for (const Enumerator& e : t.enumerators) {
    if (iequalsAscii(e.name, s)) {
      storeLe(p, static_cast<uint64_t>(e.value), size);
      return {};
    }
  }
  if (s.empty() || !(isAsciiDigit(s.front()) || s.front() == '-' || s.front() == '+'))
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
