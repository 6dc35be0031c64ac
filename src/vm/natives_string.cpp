// STRING natives. Strings are NUL-terminated bytes in the memory image; a source without a NUL
// ends at the end of memory. A destination is (address, capacity in characters) and needs
// capacity + 1 bytes inside memory; results are built in the scratch buffer (so a destination
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

#include "vm/natives.hpp"
#include "vm/value.hpp"

namespace virtcom::vm {

using bc::FaultKind;

namespace {

struct Str {
  const uint8_t* p = nullptr;
  uint64_t len = 0;
};

// A source string at addr; false if addr is outside the image.
bool readStr(const NativeContext& c, uint64_t addr, Str& out) {
  if (addr < c.nullGuard || addr >= c.memorySize) return false;
  out.p = c.memory + addr;
  const void* nul = std::memchr(out.p, 0, c.memorySize - addr);
  out.len = nul ? static_cast<const uint8_t*>(nul) - out.p : c.memorySize - addr;
  return true;
}

// Result under construction in the scratch buffer, never longer than cap.
struct Out {
  uint8_t* buf;
  uint64_t cap;
  uint64_t len = 0;
  void append(const uint8_t* p, uint64_t n) {
    n = std::min(n, cap - len);
    std::memcpy(buf + len, p, n);
    len += n;
  }
  void append(Str s) { append(s.p, s.len); }
  void append(const char* p, uint64_t n) { append(reinterpret_cast<const uint8_t*>(p), n); }
};

// Checks the destination (addr, cap) and starts a result for it.
bool openDst(const NativeContext& c, uint64_t addr, uint64_t cap, Out& out) {
  if (addr < c.nullGuard || cap >= c.memorySize || addr > c.memorySize - cap - 1) return false;
  out = Out{c.scratch, cap};
  return true;
}

void closeDst(const NativeContext& c, uint64_t addr, const Out& out, uint64_t* a) {
  std::memcpy(c.memory + addr, out.buf, out.len);
  c.memory[addr + out.len] = 0;
  a[0] = 0;
}

uint64_t clampCount(uint64_t raw, uint64_t max) {
  const int64_t n = asI(raw);
  return n < 0 ? 0 : std::min(static_cast<uint64_t>(n), max);
}

// Writes text into the destination a[0], capacity a[1].
FaultKind writeText(uint64_t* a, const NativeContext& c, const char* text, uint64_t n) {
  Out out{nullptr, 0};
  if (!openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  out.append(text, n);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

// T#1d2h3m4s5ms, like core formatTimeMs, into buf (>= 48 bytes); returns the length.
size_t formatTimeMsInto(char* buf, int64_t ms) {
  size_t n = 0;
  buf[n++] = 'T';
  buf[n++] = '#';
  uint64_t rest = ms < 0 ? 0 - static_cast<uint64_t>(ms) : static_cast<uint64_t>(ms);
  if (ms < 0) buf[n++] = '-';
  if (rest == 0) {
    std::memcpy(buf + n, "0ms", 3);
    return n + 3;
  }
  static constexpr struct { uint64_t unit; const char* suffix; } kUnits[] = {
      {86400000, "d"}, {3600000, "h"}, {60000, "m"}, {1000, "s"}, {1, "ms"}};
  for (const auto& u : kUnits) {
    if (rest < u.unit) continue;
    n = static_cast<size_t>(std::to_chars(buf + n, buf + 40, rest / u.unit).ptr - buf);
    for (const char* s = u.suffix; *s; ++s) buf[n++] = *s;
    rest %= u.unit;
  }
  return n;
}

// Shortest round-trip text with a decimal point, like core formatReal/formatLreal.
template <typename F>
size_t formatFloatInto(char* buf, F v) {
  char* end = std::to_chars(buf, buf + 60, v).ptr;
  size_t n = static_cast<size_t>(end - buf);
  bool marked = false;
  for (size_t i = 0; i < n; ++i) {
    if (buf[i] == 'e') buf[i] = 'E';
    if (buf[i] == '.' || buf[i] == 'E' || buf[i] == 'n') marked = true;
  }
  if (!marked) {
    buf[n++] = '.';
    buf[n++] = '0';
  }
  return n;
}

bool isSpace(uint8_t ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

}  // namespace

FaultKind native_STR_ASSIGN(uint64_t* a, const NativeContext& c) {
  Str s;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], s) || !openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  out.append(s);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_LEN(uint64_t* a, const NativeContext& c) {
  Str s;
  if (!readStr(c, a[0], s)) return FaultKind::InvalidPointer;
  a[0] = s.len;
  return FaultKind::None;
}

FaultKind native_STR_CMP(uint64_t* a, const NativeContext& c) {
  Str x, y;
  if (!readStr(c, a[0], x) || !readStr(c, a[1], y)) return FaultKind::InvalidPointer;
  const uint64_t n = std::min(x.len, y.len);
  int cmp = n ? std::memcmp(x.p, y.p, n) : 0;
  if (cmp == 0) cmp = x.len < y.len ? -1 : x.len > y.len ? 1 : 0;
  a[0] = fromI(cmp < 0 ? -1 : cmp > 0 ? 1 : 0);
  return FaultKind::None;
}

FaultKind native_STR_LEFT(uint64_t* a, const NativeContext& c) {
  Str s;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], s) || !openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  out.append(s.p, clampCount(a[3], s.len));
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_RIGHT(uint64_t* a, const NativeContext& c) {
  Str s;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], s) || !openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  const uint64_t n = clampCount(a[3], s.len);
  out.append(s.p + (s.len - n), n);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_MID(uint64_t* a, const NativeContext& c) {
  Str s;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], s) || !openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  const int64_t p = asI(a[4]);
  if (p >= 1 && static_cast<uint64_t>(p) <= s.len) {
    const uint64_t start = static_cast<uint64_t>(p) - 1;
    out.append(s.p + start, clampCount(a[3], s.len - start));
  }
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_CONCAT(uint64_t* a, const NativeContext& c) {
  Str x, y;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], x) || !readStr(c, a[3], y) || !openDst(c, a[0], a[1], out))
    return FaultKind::InvalidPointer;
  out.append(x);
  out.append(y);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_INSERT(uint64_t* a, const NativeContext& c) {
  Str x, y;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], x) || !readStr(c, a[3], y) || !openDst(c, a[0], a[1], out))
    return FaultKind::InvalidPointer;
  const uint64_t p = clampCount(a[4], x.len);
  out.append(x.p, p);
  out.append(y);
  out.append(x.p + p, x.len - p);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_DELETE(uint64_t* a, const NativeContext& c) {
  Str s;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], s) || !openDst(c, a[0], a[1], out)) return FaultKind::InvalidPointer;
  const int64_t p = asI(a[4]);
  if (p >= 1 && static_cast<uint64_t>(p) <= s.len) {
    const uint64_t start = static_cast<uint64_t>(p) - 1;
    const uint64_t n = clampCount(a[3], s.len - start);
    out.append(s.p, start);
    out.append(s.p + start + n, s.len - start - n);
  } else {
    out.append(s);
  }
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_REPLACE(uint64_t* a, const NativeContext& c) {
  Str x, y;
  Out out{nullptr, 0};
  if (!readStr(c, a[2], x) || !readStr(c, a[3], y) || !openDst(c, a[0], a[1], out))
    return FaultKind::InvalidPointer;
  const int64_t p = asI(a[5]);
  const uint64_t start = p < 1 ? 0 : std::min(static_cast<uint64_t>(p) - 1, x.len);
  const uint64_t n = clampCount(a[4], x.len - start);
  out.append(x.p, start);
  out.append(y);
  out.append(x.p + start + n, x.len - start - n);
  closeDst(c, a[0], out, a);
  return FaultKind::None;
}

FaultKind native_STR_FIND(uint64_t* a, const NativeContext& c) {
  Str x, y;
  if (!readStr(c, a[0], x) || !readStr(c, a[1], y)) return FaultKind::InvalidPointer;
  a[0] = 0;
  if (y.len == 0 || y.len > x.len) return FaultKind::None;
  for (uint64_t i = 0; i + y.len <= x.len; ++i) {
    if (std::memcmp(x.p + i, y.p, y.len) == 0) {
      a[0] = i + 1;
      break;
    }
  }
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

FaultKind native_STR_FROM_REAL(uint64_t* a, const NativeContext& c) {
  char buf[64];
  return writeText(a, c, buf, formatFloatInto(buf, static_cast<float>(asF(a[2]))));
}

FaultKind native_STR_FROM_LREAL(uint64_t* a, const NativeContext& c) {
  char buf[64];
  return writeText(a, c, buf, formatFloatInto(buf, asF(a[2])));
}

FaultKind native_STR_FROM_TIME(uint64_t* a, const NativeContext& c) {
  char buf[64];
  return writeText(a, c, buf, formatTimeMsInto(buf, asI(a[2])));
}

FaultKind native_STR_FROM_BOOL(uint64_t* a, const NativeContext& c) {
  return a[2] != 0 ? writeText(a, c, "TRUE", 4) : writeText(a, c, "FALSE", 5);
}

// Leading blanks, an optional sign, then decimal digits; saturates on overflow.
FaultKind native_STR_TO_I(uint64_t* a, const NativeContext& c) {
  Str s;
  if (!readStr(c, a[0], s)) return FaultKind::InvalidPointer;
  uint64_t i = 0;
  while (i < s.len && isSpace(s.p[i])) ++i;
  bool negative = false;
  if (i < s.len && (s.p[i] == '-' || s.p[i] == '+')) negative = s.p[i++] == '-';
  const uint64_t limit = negative ? uint64_t{1} << 63 : (uint64_t{1} << 63) - 1;
  uint64_t v = 0;
  for (; i < s.len && s.p[i] >= '0' && s.p[i] <= '9'; ++i) {
    const uint64_t d = s.p[i] - '0';
    v = v > (limit - d) / 10 ? limit : v * 10 + d;
  }
  a[0] = negative ? 0 - v : v;
  return FaultKind::None;
}

// Leading blanks, then the longest prefix that parses as a decimal real (1.5, -2E3).
FaultKind native_STR_TO_F(uint64_t* a, const NativeContext& c) {
  Str s;
  if (!readStr(c, a[0], s)) return FaultKind::InvalidPointer;
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

}  // namespace virtcom::vm
