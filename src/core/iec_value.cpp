#include "core/iec_value.hpp"

#include <charconv>
#include <cstdio>

#include "core/ascii.hpp"
#include "core/duration_units.hpp"

namespace virtcom {

bool elemTypeByName(std::string_view name, ElemType& out) {
  if (iequalsAscii(name, "TOD")) { out = ElemType::Tod; return true; }
  if (iequalsAscii(name, "DT")) { out = ElemType::Dt; return true; }
  if (iequalsAscii(name, "LTOD")) { out = ElemType::Ltod; return true; }
  if (iequalsAscii(name, "LDT")) { out = ElemType::Ldt; return true; }
  for (size_t i = 0; i < std::size(kElemTypeInfo); ++i) {
    if (iequalsAscii(name, kElemTypeInfo[i].name)) {
      out = static_cast<ElemType>(i);
      return true;
    }
  }
  return false;
}

bool isIntegerKind(ElemKind k) {
  return k == ElemKind::Bits || k == ElemKind::Signed || k == ElemKind::Unsigned;
}

uint32_t bitWidth(ElemType t) {
  if (t == ElemType::Bool) return 1;
  return elemTypeInfo(t).sizeBytes * 8;
}

int64_t timeUnitNs(ElemType t) {
  switch (t) {
    case ElemType::Time:
    case ElemType::Tod: return 1'000'000;
    case ElemType::Date:
    case ElemType::Dt: return 1'000'000'000;
    case ElemType::Ltime:
    case ElemType::Ldate:
    case ElemType::Ltod:
    case ElemType::Ldt: return 1;
    default: return 0;
  }
}

DatePart datePart(ElemType t) {
  switch (t) {
    case ElemType::Date:
    case ElemType::Ldate: return DatePart::Day;
    case ElemType::Tod:
    case ElemType::Ltod: return DatePart::Clock;
    case ElemType::Dt:
    case ElemType::Ldt: return DatePart::Both;
    default: return DatePart::None;
  }
}

namespace {

// Appends to a caller's buffer of kIecTextMax bytes. The texts of real values are far
// shorter; the bound only matters for the garbage a faulty program may format.
struct TextBuf {
  char* p;
  size_t n = 0;
  void add(std::string_view s) {
    for (char c : s)
      if (n < kIecTextMax) p[n++] = c;
  }
  void addNumber(uint64_t v, int minDigits = 1) {
    char digits[24];
    char* end = std::to_chars(digits, digits + sizeof digits, v).ptr;
    for (int pad = minDigits - static_cast<int>(end - digits); pad > 0; --pad) add("0");
    add(std::string_view(digits, static_cast<size_t>(end - digits)));
  }
};

void addUnit(TextBuf& out, uint64_t& rest, uint64_t unit, std::string_view suffix) {
  if (rest >= unit) {
    out.addNumber(rest / unit);
    out.add(suffix);
    rest %= unit;
  }
}

size_t formatDurationInto(char* buf, const char* prefix, int64_t value, bool nanos) {
  TextBuf out{buf};
  out.add(prefix);
  // the magnitude as unsigned, so INT64_MIN has one too
  uint64_t rest = value < 0 ? 0 - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  if (value < 0) out.add("-");
  if (value == 0) {
    out.add(nanos ? "0ns" : "0ms");
    return out.n;
  }
  // TIME counts milliseconds, so it stops at ms; LTIME goes down to ns.
  constexpr uint64_t kNsPerMs = 1'000'000;
  for (const DurationUnit& unit : kDurationUnits) {
    if (!nanos && unit.ns < kNsPerMs) break;
    addUnit(out, rest, nanos ? unit.ns : unit.ns / kNsPerMs, unit.iec);
  }
  return out.n;
}

}  // namespace

size_t formatTimeMsInto(char* buf, int64_t ms) { return formatDurationInto(buf, "T#", ms, false); }
size_t formatLtimeNsInto(char* buf, int64_t ns) { return formatDurationInto(buf, "LTIME#", ns, true); }

template <typename T>
static std::string asString(size_t (*formatInto)(char*, T), T value) {
  char buf[kIecTextMax];
  return std::string(buf, formatInto(buf, value));
}

std::string formatTimeMs(int64_t ms) { return asString(formatTimeMsInto, ms); }
std::string formatLtimeNs(int64_t ns) { return asString(formatLtimeNsInto, ns); }

int64_t daysFromCivil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

void civilFromDays(int64_t z, int64_t& y, unsigned& m, unsigned& d) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  y = static_cast<int64_t>(yoe) + era * 400;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  d = doy - (153 * mp + 2) / 5 + 1;
  m = mp < 10 ? mp + 3 : mp - 9;
  y += m <= 2;
}

static void addDate(TextBuf& out, int64_t seconds) {
  int64_t days = seconds / 86400 - (seconds % 86400 < 0 ? 1 : 0);  // floor, also for INT64_MIN
  int64_t y;
  unsigned m, d;
  civilFromDays(days, y, m, d);
  if (y < 0) out.add("-");
  out.addNumber(static_cast<uint64_t>(y < 0 ? -y : y), 4);
  out.add("-");
  out.addNumber(m, 2);
  out.add("-");
  out.addNumber(d, 2);
}

constexpr int64_t kNsPerDay = 86'400'000'000'000;

// A TOD beyond a day (it is a 32-bit count of milliseconds) shows its time within the day;
// the fraction of a second has as many digits as it needs (none, up to 9 for LTOD).
static void addClock(TextBuf& out, int64_t ns) {
  int64_t nsOfDay = ((ns % kNsPerDay) + kNsPerDay) % kNsPerDay;
  int64_t s = nsOfDay / 1'000'000'000;
  out.addNumber(static_cast<uint64_t>(s / 3600), 2);
  out.add(":");
  out.addNumber(static_cast<uint64_t>((s / 60) % 60), 2);
  out.add(":");
  out.addNumber(static_cast<uint64_t>(s % 60), 2);
  if (int64_t frac = nsOfDay % 1'000'000'000) {
    out.add(".");
    out.addNumber(static_cast<uint64_t>(frac), 9);
    while (out.p[out.n - 1] == '0') --out.n;
  }
}

size_t formatDateInto(char* buf, int64_t seconds) {
  TextBuf out{buf};
  out.add("D#");
  addDate(out, seconds);
  return out.n;
}

size_t formatTimeOfDayInto(char* buf, int64_t ms) {
  TextBuf out{buf};
  out.add("TOD#");
  addClock(out, (ms % 86'400'000) * 1'000'000);  // the day first: any 64-bit value of ms prints without overflow
  return out.n;
}

size_t formatDateAndTimeInto(char* buf, int64_t seconds) {
  TextBuf out{buf};
  out.add("DT#");
  addDate(out, seconds);
  out.add("-");
  addClock(out, (seconds % 86400) * 1'000'000'000);
  return out.n;
}

// The long date types count nanoseconds; their dates are the floor of the day.
static int64_t floorSeconds(int64_t ns) { return ns / 1'000'000'000 - (ns % 1'000'000'000 < 0 ? 1 : 0); }

size_t formatLdateInto(char* buf, int64_t ns) {
  TextBuf out{buf};
  out.add("LDATE#");
  addDate(out, floorSeconds(ns));
  return out.n;
}

size_t formatLtodInto(char* buf, int64_t ns) {
  TextBuf out{buf};
  out.add("LTOD#");
  addClock(out, ns);
  return out.n;
}

size_t formatLdtInto(char* buf, int64_t ns) {
  TextBuf out{buf};
  out.add("LDT#");
  addDate(out, floorSeconds(ns));
  out.add("-");
  addClock(out, ns);
  return out.n;
}

template <typename F>
static size_t formatFloatInto(char* buf, F v) {
  size_t n = static_cast<size_t>(std::to_chars(buf, buf + kIecTextMax - 2, v).ptr - buf);
  bool marked = false;  // a '.', an exponent, or nan/inf (which contain 'n')
  for (size_t i = 0; i < n; ++i) {
    if (buf[i] == 'e') buf[i] = 'E';
    marked = marked || buf[i] == '.' || buf[i] == 'E' || buf[i] == 'n';
  }
  if (!marked) {
    buf[n++] = '.';
    buf[n++] = '0';
  }
  return n;
}

size_t formatRealInto(char* buf, float v) { return formatFloatInto(buf, v); }
size_t formatLrealInto(char* buf, double v) { return formatFloatInto(buf, v); }

std::string formatDate(int64_t seconds) { return asString(formatDateInto, seconds); }
std::string formatTimeOfDay(int64_t ms) { return asString(formatTimeOfDayInto, ms); }
std::string formatDateAndTime(int64_t seconds) { return asString(formatDateAndTimeInto, seconds); }
std::string formatLdate(int64_t ns) { return asString(formatLdateInto, ns); }
std::string formatLtod(int64_t ns) { return asString(formatLtodInto, ns); }
std::string formatLdt(int64_t ns) { return asString(formatLdtInto, ns); }
std::string formatReal(float v) { return asString(formatRealInto, v); }
std::string formatLreal(double v) { return asString(formatLrealInto, v); }

std::string quoteString(std::string_view raw) {
  std::string out = "'";
  for (unsigned char c : raw) {
    switch (c) {
      case '\'': out += "$'"; break;
      case '$': out += "$$"; break;
      case '\n': out += "$N"; break;
      case '\r': out += "$R"; break;
      case '\t': out += "$T"; break;
      case '\f': out += "$P"; break;
      default:
        if (c < 0x20 || c >= 0x7f) {
          char buf[4];
          std::snprintf(buf, sizeof buf, "$%02X", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "'";
}

}  // namespace virtcom
