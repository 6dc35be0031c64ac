// STRING and WSTRING natives. A STRING is NUL-terminated bytes in the memory image, a WSTRING
// UTF-16LE code units ended by a zero unit; a source without a terminator ends at the end of
// memory. A destination is (address, capacity in characters) and needs capacity + 1 characters
// inside memory; results are built in the scratch buffer (so a destination
// may alias a source), truncated to the capacity and NUL-terminated. A source or destination
// outside [kNullGuard, memorySize) raises InvalidPointer. Positions are 1-based (IEC).
//
// Edge positions (the standard leaves them open; these follow CODESYS where it is known):
//   LEFT/RIGHT: L < 0 is 0, L > length is the whole string.
//   MID(s, L, P): P < 1 or P > length gives ''; L is clamped to the rest of the string.
//   INSERT(a, b, P): P < 0 is 0 (insert at the front), P > length appends.
//   DELETE(s, L, P): P < 1 or P > length leaves s unchanged; L is clamped to the rest.
//   REPLACE(a, b, L, P): P is clamped to 1..length+1, L to the rest; = INSERT(DELETE(a,L,P),b,P-1).
//   FIND(a, b): 0 when b is empty or not found.
#include <algorithm>
#include <charconv>
#include <cstring>

#include "core/ascii.hpp"
#include "core/iec_literal.hpp"
#include "core/iec_value.hpp"
#include "vm/natives.hpp"
#include "vm/value.hpp"

namespace virtcom::vm {

using bc::FaultKind;

namespace {

// A source text of W-byte code units (W = 1: STRING, W = 2: WSTRING, UTF-16LE); len in units.
template <unsigned W>
struct Text {
  const uint8_t* p = nullptr;
  uint64_t len = 0;
};

std::string_view asView(const Text<1>& s) { return {reinterpret_cast<const char*>(s.p), s.len}; }

template <unsigned W>
uint32_t unitAt(const uint8_t* p, uint64_t i) {
  return W == 1 ? p[i] : static_cast<uint32_t>(p[2 * i] | (p[2 * i + 1] << 8));
}

// A source text at addr; false if addr is outside the image. Without a terminator the text
// ends at the end of memory.
template <unsigned W>
bool readText(const NativeContext& c, uint64_t addr, Text<W>& out) {
  if (addr < c.nullGuard || addr >= c.memorySize) return false;
  out.p = c.memory + addr;
  const uint64_t maxUnits = (c.memorySize - addr) / W;
  if constexpr (W == 1) {
    const void* nul = std::memchr(out.p, 0, maxUnits);
    out.len = nul ? static_cast<uint64_t>(static_cast<const uint8_t*>(nul) - out.p) : maxUnits;
  } else {
    out.len = 0;
    while (out.len < maxUnits && unitAt<W>(out.p, out.len) != 0) ++out.len;
  }
  return true;
}

// Result under construction in the scratch buffer, never longer than cap units.
template <unsigned W>
struct Out {
  uint8_t* buf = nullptr;
  uint64_t cap = 0;
  uint64_t len = 0;
  void append(const uint8_t* p, uint64_t n) {
    n = std::min(n, cap - len);
    std::memcpy(buf + W * len, p, W * n);
    len += n;
  }
  void append(Text<W> s) { append(s.p, s.len); }
  void appendUnit(uint32_t unit) {
    if (len == cap) return;
    buf[W * len] = static_cast<uint8_t>(unit);
    if constexpr (W == 2) buf[W * len + 1] = static_cast<uint8_t>(unit >> 8);
    ++len;
  }
};

// Checks the destination (addr, cap units + terminator) and starts a result for it.
template <unsigned W>
bool openDst(const NativeContext& c, uint64_t addr, uint64_t cap, Out<W>& out) {
  if (addr < c.nullGuard || cap >= c.memorySize / W || addr > c.memorySize - W * (cap + 1)) return false;
  out = Out<W>{c.scratch, cap, 0};
  return true;
}

template <unsigned W>
void closeDst(const NativeContext& c, uint64_t addr, const Out<W>& out, uint64_t* a) {
  std::memcpy(c.memory + addr, out.buf, W * out.len);
  std::memset(c.memory + addr + W * out.len, 0, W);
  a[0] = 0;
}

uint64_t clampCount(uint64_t raw, uint64_t max) {
  const int64_t n = asI(raw);
  return n < 0 ? 0 : std::min(static_cast<uint64_t>(n), max);
}

// The common shape of (dst, cap, sources...) natives: read the sources, open the destination,
// let `build` append the result, close. Sources are read before anything is written, and the
// result is built in scratch, so the destination may alias any source.
template <unsigned W, unsigned NSrc, typename Build>
FaultKind withDst(uint64_t* a, const NativeContext& c, Build build) {
  Text<W> src[NSrc > 0 ? NSrc : 1];
  for (unsigned i = 0; i < NSrc; ++i)
    if (!readText<W>(c, a[2 + i], src[i])) return FaultKind::InvalidPointer;
  Out<W> out;
  if (!openDst<W>(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  build(out, src);
  closeDst<W>(c, a[0], out, a);
  return FaultKind::None;
}

template <unsigned W>
FaultKind assign(uint64_t* a, const NativeContext& c) {
  return withDst<W, 1>(a, c, [](Out<W>& out, const Text<W>* s) { out.append(s[0]); });
}

template <unsigned W>
FaultKind length(uint64_t* a, const NativeContext& c) {
  Text<W> s;
  if (!readText<W>(c, a[0], s)) return FaultKind::InvalidPointer;
  a[0] = s.len;
  return FaultKind::None;
}

template <unsigned W>
FaultKind compare(uint64_t* a, const NativeContext& c) {
  Text<W> x, y;
  if (!readText<W>(c, a[0], x) || !readText<W>(c, a[1], y)) return FaultKind::InvalidPointer;
  const uint64_t n = std::min(x.len, y.len);
  int cmp = 0;
  for (uint64_t i = 0; i < n && cmp == 0; ++i) {
    const uint32_t u = unitAt<W>(x.p, i), v = unitAt<W>(y.p, i);
    cmp = u < v ? -1 : u > v ? 1 : 0;
  }
  if (cmp == 0) cmp = x.len < y.len ? -1 : x.len > y.len ? 1 : 0;
  a[0] = fromI(cmp);
  return FaultKind::None;
}

template <unsigned W>
FaultKind left(uint64_t* a, const NativeContext& c) {
  const uint64_t l = a[3];
  return withDst<W, 1>(a, c, [l](Out<W>& out, const Text<W>* s) { out.append(s[0].p, clampCount(l, s[0].len)); });
}

template <unsigned W>
FaultKind right(uint64_t* a, const NativeContext& c) {
  const uint64_t l = a[3];
  return withDst<W, 1>(a, c, [l](Out<W>& out, const Text<W>* s) {
    const uint64_t n = clampCount(l, s[0].len);
    out.append(s[0].p + W * (s[0].len - n), n);
  });
}

template <unsigned W>
FaultKind mid(uint64_t* a, const NativeContext& c) {
  const uint64_t l = a[3];
  const int64_t p = asI(a[4]);
  return withDst<W, 1>(a, c, [l, p](Out<W>& out, const Text<W>* s) {
    if (p < 1 || static_cast<uint64_t>(p) > s[0].len) return;
    const uint64_t start = static_cast<uint64_t>(p) - 1;
    out.append(s[0].p + W * start, clampCount(l, s[0].len - start));
  });
}

template <unsigned W>
FaultKind concat(uint64_t* a, const NativeContext& c) {
  return withDst<W, 2>(a, c, [](Out<W>& out, const Text<W>* s) {
    out.append(s[0]);
    out.append(s[1]);
  });
}

template <unsigned W>
FaultKind insert(uint64_t* a, const NativeContext& c) {
  const uint64_t rawP = a[4];
  return withDst<W, 2>(a, c, [rawP](Out<W>& out, const Text<W>* s) {
    const uint64_t p = clampCount(rawP, s[0].len);
    out.append(s[0].p, p);
    out.append(s[1]);
    out.append(s[0].p + W * p, s[0].len - p);
  });
}

template <unsigned W>
FaultKind erase(uint64_t* a, const NativeContext& c) {
  const uint64_t l = a[3];
  const int64_t p = asI(a[4]);
  return withDst<W, 1>(a, c, [l, p](Out<W>& out, const Text<W>* s) {
    if (p < 1 || static_cast<uint64_t>(p) > s[0].len) return out.append(s[0]);
    const uint64_t start = static_cast<uint64_t>(p) - 1;
    const uint64_t n = clampCount(l, s[0].len - start);
    out.append(s[0].p, start);
    out.append(s[0].p + W * (start + n), s[0].len - start - n);
  });
}

template <unsigned W>
FaultKind replace(uint64_t* a, const NativeContext& c) {
  const uint64_t l = a[4];
  const int64_t p = asI(a[5]);
  return withDst<W, 2>(a, c, [l, p](Out<W>& out, const Text<W>* s) {
    const uint64_t start = p < 1 ? 0 : std::min(static_cast<uint64_t>(p) - 1, s[0].len);
    const uint64_t n = clampCount(l, s[0].len - start);
    out.append(s[0].p, start);
    out.append(s[1]);
    out.append(s[0].p + W * (start + n), s[0].len - start - n);
  });
}

template <unsigned W>
FaultKind find(uint64_t* a, const NativeContext& c) {
  Text<W> x, y;
  if (!readText<W>(c, a[0], x) || !readText<W>(c, a[1], y)) return FaultKind::InvalidPointer;
  a[0] = 0;
  if (y.len == 0 || y.len > x.len) return FaultKind::None;
  for (uint64_t i = 0; i + y.len <= x.len; ++i) {
    if (std::memcmp(x.p + W * i, y.p, W * y.len) == 0) {
      a[0] = i + 1;
      break;
    }
  }
  return FaultKind::None;
}

// Writes text into the destination a[0], capacity a[1].
FaultKind writeText(uint64_t* a, const NativeContext& c, const char* text, uint64_t n) {
  return withDst<1, 0>(a, c, [text, n](Out<1>& out, const Text<1>*) {
    out.append(reinterpret_cast<const uint8_t*>(text), n);
  });
}

bool isSpace(uint8_t ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

}  // namespace

FaultKind native_STR_ASSIGN(uint64_t* a, const NativeContext& c) { return assign<1>(a, c); }
FaultKind native_STR_LEN(uint64_t* a, const NativeContext& c) { return length<1>(a, c); }
FaultKind native_STR_CMP(uint64_t* a, const NativeContext& c) { return compare<1>(a, c); }
FaultKind native_STR_LEFT(uint64_t* a, const NativeContext& c) { return left<1>(a, c); }
FaultKind native_STR_RIGHT(uint64_t* a, const NativeContext& c) { return right<1>(a, c); }
FaultKind native_STR_MID(uint64_t* a, const NativeContext& c) { return mid<1>(a, c); }
FaultKind native_STR_CONCAT(uint64_t* a, const NativeContext& c) { return concat<1>(a, c); }
FaultKind native_STR_INSERT(uint64_t* a, const NativeContext& c) { return insert<1>(a, c); }
FaultKind native_STR_DELETE(uint64_t* a, const NativeContext& c) { return erase<1>(a, c); }
FaultKind native_STR_REPLACE(uint64_t* a, const NativeContext& c) { return replace<1>(a, c); }
FaultKind native_STR_FIND(uint64_t* a, const NativeContext& c) { return find<1>(a, c); }

FaultKind native_WSTR_ASSIGN(uint64_t* a, const NativeContext& c) { return assign<2>(a, c); }
FaultKind native_WSTR_LEN(uint64_t* a, const NativeContext& c) { return length<2>(a, c); }
FaultKind native_WSTR_CMP(uint64_t* a, const NativeContext& c) { return compare<2>(a, c); }
FaultKind native_WSTR_LEFT(uint64_t* a, const NativeContext& c) { return left<2>(a, c); }
FaultKind native_WSTR_RIGHT(uint64_t* a, const NativeContext& c) { return right<2>(a, c); }
FaultKind native_WSTR_MID(uint64_t* a, const NativeContext& c) { return mid<2>(a, c); }
FaultKind native_WSTR_CONCAT(uint64_t* a, const NativeContext& c) { return concat<2>(a, c); }
FaultKind native_WSTR_INSERT(uint64_t* a, const NativeContext& c) { return insert<2>(a, c); }
FaultKind native_WSTR_DELETE(uint64_t* a, const NativeContext& c) { return erase<2>(a, c); }
FaultKind native_WSTR_REPLACE(uint64_t* a, const NativeContext& c) { return replace<2>(a, c); }
FaultKind native_WSTR_FIND(uint64_t* a, const NativeContext& c) { return find<2>(a, c); }

// STRING_TO_WSTRING: each byte becomes the character with that code (Latin-1).
FaultKind native_WSTR_FROM_STR(uint64_t* a, const NativeContext& c) {
  Text<1> s;
  if (!readText<1>(c, a[2], s)) return FaultKind::InvalidPointer;
  Out<2> out;
  if (!openDst<2>(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  for (uint64_t i = 0; i < s.len && out.len < out.cap; ++i) out.appendUnit(s.p[i]);
  closeDst<2>(c, a[0], out, a);
  return FaultKind::None;
}

// WSTRING_TO_STRING: characters 1..255 map to bytes, anything above becomes '?'.
FaultKind native_STR_FROM_WSTR(uint64_t* a, const NativeContext& c) {
  Text<2> w;
  if (!readText<2>(c, a[2], w)) return FaultKind::InvalidPointer;
  Out<1> out;
  if (!openDst<1>(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  for (uint64_t i = 0; i < w.len && out.len < out.cap; ++i) {
    const uint32_t u = unitAt<2>(w.p, i);
    out.appendUnit(u < 256 ? u : '?');
  }
  closeDst<1>(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_FROM_I(uint64_t* a, const NativeContext& c) {
  char buf[32];
  const char* end = std::to_chars(buf, buf + sizeof buf, asI(a[2])).ptr;
  return writeText(a, c, buf, static_cast<uint64_t>(end - buf));
}

FaultKind native_STR_FROM_U(uint64_t* a, const NativeContext& c) {
  char buf[32];
  const char* end = std::to_chars(buf, buf + sizeof buf, a[2]).ptr;
  return writeText(a, c, buf, static_cast<uint64_t>(end - buf));
}

// The IEC literal texts of core/iec_value.hpp, written without allocating.
template <typename T>
FaultKind writeFormatted(uint64_t* a, const NativeContext& c, size_t (*formatInto)(char*, T), T value) {
  char buf[kIecTextMax];
  return writeText(a, c, buf, formatInto(buf, value));
}

FaultKind native_STR_FROM_REAL(uint64_t* a, const NativeContext& c) {
  return writeFormatted(a, c, formatRealInto, static_cast<float>(asF(a[2])));
}
FaultKind native_STR_FROM_LREAL(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatLrealInto, asF(a[2])); }
FaultKind native_STR_FROM_TIME(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatTimeMsInto, asI(a[2])); }
FaultKind native_STR_FROM_LTIME(uint64_t* a, const NativeContext& c) {
  return writeFormatted(a, c, formatLtimeNsInto, asI(a[2]));
}
FaultKind native_STR_FROM_DATE(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatDateInto, asI(a[2])); }
FaultKind native_STR_FROM_TOD(uint64_t* a, const NativeContext& c) {
  return writeFormatted(a, c, formatTimeOfDayInto, asI(a[2]));
}
FaultKind native_STR_FROM_DT(uint64_t* a, const NativeContext& c) {
  return writeFormatted(a, c, formatDateAndTimeInto, asI(a[2]));
}

FaultKind native_STR_FROM_BOOL(uint64_t* a, const NativeContext& c) {
  return a[2] != 0 ? writeText(a, c, "TRUE", 4) : writeText(a, c, "FALSE", 5);
}

// STRING_TO_<integer>: IEC integer text (42, -7, 16#FF, INT#5), 0 if there is none.
FaultKind native_STR_TO_I(uint64_t* a, const NativeContext& c) {
  Text<1> s;
  if (!readText<1>(c, a[0], s)) return FaultKind::InvalidPointer;
  int64_t v = 0;
  if (!parseIntegerText(asView(s), v)) v = 0;
  a[0] = static_cast<uint64_t>(v);
  return FaultKind::None;
}

// STRING_TO_BOOL: TRUE/FALSE in any case, or an integer (non-zero is TRUE).
FaultKind native_STR_TO_BOOL(uint64_t* a, const NativeContext& c) {
  Text<1> s;
  if (!readText<1>(c, a[0], s)) return FaultKind::InvalidPointer;
  std::string_view text = asView(s);
  while (!text.empty() && isSpace(static_cast<uint8_t>(text.front()))) text.remove_prefix(1);
  int64_t v = 0;
  bool isTrue = istartsWithAscii(text, "TRUE");
  a[0] = isTrue || (parseIntegerText(text, v) && v != 0) ? 1 : 0;
  return FaultKind::None;
}

// STRING_TO_TIME and friends: the literal text with or without its prefix, 0 if malformed.
template <LiteralFamily F>
FaultKind timeOrDateFromText(uint64_t* a, const NativeContext& c) {
  Text<1> s;
  if (!readText<1>(c, a[0], s)) return FaultKind::InvalidPointer;
  int64_t v = 0;
  if (!parseTimeOrDateText(asView(s), F, v)) v = 0;
  a[0] = static_cast<uint64_t>(v);
  return FaultKind::None;
}

FaultKind native_STR_TO_TIME(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Time>(a, c); }
FaultKind native_STR_TO_LTIME(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Ltime>(a, c); }
FaultKind native_STR_TO_DATE(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Date>(a, c); }
FaultKind native_STR_TO_TOD(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Tod>(a, c); }
FaultKind native_STR_TO_DT(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Dt>(a, c); }

// Leading blanks, then the longest prefix that parses as a decimal real (1.5, -2E3).
FaultKind native_STR_TO_F(uint64_t* a, const NativeContext& c) {
  Text<1> s;
  if (!readText<1>(c, a[0], s)) return FaultKind::InvalidPointer;
  uint64_t i = 0;
  while (i < s.len && isSpace(s.p[i])) ++i;
  if (i < s.len && s.p[i] == '+') ++i;
  const char* first = reinterpret_cast<const char*>(s.p + i);
  const char* last = reinterpret_cast<const char*>(s.p + s.len);
  double v = 0.0;
  auto res = std::from_chars(first, last, v, std::chars_format::general);
  if (res.ec == std::errc::result_out_of_range) v = 0.0;
  a[0] = fromF(res.ec == std::errc() || res.ec == std::errc::result_out_of_range ? v : 0.0);
  return FaultKind::None;
}

FaultKind native_STR_FROM_LDATE(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatLdateInto, asI(a[2])); }
FaultKind native_STR_FROM_LTOD(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatLtodInto, asI(a[2])); }
FaultKind native_STR_FROM_LDT(uint64_t* a, const NativeContext& c) { return writeFormatted(a, c, formatLdtInto, asI(a[2])); }
FaultKind native_STR_TO_LDATE(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Ldate>(a, c); }
FaultKind native_STR_TO_LTOD(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Ltod>(a, c); }
FaultKind native_STR_TO_LDT(uint64_t* a, const NativeContext& c) { return timeOrDateFromText<LiteralFamily::Ldt>(a, c); }

namespace {

// CHAR_TO_STRING / WCHAR_TO_WSTRING: a text of the one character (the NUL character ends a
// text, so CHAR#0 gives the empty text).
template <unsigned W>
FaultKind fromCharacter(uint64_t* a, const NativeContext& c) {
  const uint32_t unit = static_cast<uint32_t>(a[2] & (W == 1 ? 0xFFu : 0xFFFFu));
  return withDst<W, 0>(a, c, [unit](Out<W>& out, const Text<W>*) {
    if (unit != 0) out.appendUnit(unit);
  });
}

template <unsigned W>
FaultKind firstCharacter(uint64_t* a, const NativeContext& c) {
  Text<W> s;
  if (!readText<W>(c, a[0], s)) return FaultKind::InvalidPointer;
  a[0] = s.len > 0 ? unitAt<W>(s.p, 0) : 0;
  return FaultKind::None;
}

}  // namespace

FaultKind native_STR_FROM_CHAR(uint64_t* a, const NativeContext& c) { return fromCharacter<1>(a, c); }
FaultKind native_WSTR_FROM_WCHAR(uint64_t* a, const NativeContext& c) { return fromCharacter<2>(a, c); }
FaultKind native_STR_TO_CHAR(uint64_t* a, const NativeContext& c) { return firstCharacter<1>(a, c); }
FaultKind native_WSTR_TO_WCHAR(uint64_t* a, const NativeContext& c) { return firstCharacter<2>(a, c); }

}  // namespace virtcom::vm
