#include "core/iec_value.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>

namespace virtcom {

static const ElemTypeInfo kElemInfo[] = {
#define X(e, name, size, kind) {name, size, ElemKind::kind},
#include "core/elementary_types.def"
#undef X
};

const ElemTypeInfo& elemTypeInfo(ElemType t) { return kElemInfo[static_cast<size_t>(t)]; }

static bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

bool elemTypeByName(std::string_view name, ElemType& out) {
  if (equalsNoCase(name, "TOD")) { out = ElemType::Tod; return true; }
  if (equalsNoCase(name, "DT")) { out = ElemType::Dt; return true; }
  for (size_t i = 0; i < std::size(kElemInfo); ++i) {
    if (equalsNoCase(name, kElemInfo[i].name)) {
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

static void appendUnit(std::string& out, uint64_t& rest, uint64_t unit, const char* suffix) {
  if (rest >= unit) {
    out += std::to_string(rest / unit) + suffix;
    rest %= unit;
  }
}

static std::string formatDuration(const char* prefix, int64_t value, bool nanos) {
  std::string out = prefix;
  // the magnitude as unsigned, so INT64_MIN has one too
  uint64_t rest = value < 0 ? 0 - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  if (value < 0) out += '-';
  if (value == 0) return out + (nanos ? "0ns" : "0ms");
  uint64_t ms = nanos ? 1000000 : 1;
  appendUnit(out, rest, 86400000 * ms, "d");
  appendUnit(out, rest, 3600000 * ms, "h");
  appendUnit(out, rest, 60000 * ms, "m");
  appendUnit(out, rest, 1000 * ms, "s");
  appendUnit(out, rest, ms, "ms");
  if (nanos) {
    appendUnit(out, rest, 1000, "us");
    appendUnit(out, rest, 1, "ns");
  }
  return out;
}

std::string formatTimeMs(int64_t ms) { return formatDuration("T#", ms, false); }
std::string formatLtimeNs(int64_t ns) { return formatDuration("LTIME#", ns, true); }

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

static std::string dateText(int64_t seconds) {
  int64_t days = seconds >= 0 ? seconds / 86400 : -((-seconds + 86399) / 86400);
  int64_t y;
  unsigned m, d;
  civilFromDays(days, y, m, d);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%04lld-%02u-%02u", static_cast<long long>(y), m, d);
  return buf;
}

static std::string clockText(int64_t msOfDay) {
  char buf[32];
  int64_t s = msOfDay / 1000;
  std::snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld", static_cast<long long>(s / 3600),
                static_cast<long long>((s / 60) % 60), static_cast<long long>(s % 60));
  std::string out = buf;
  if (int64_t frac = msOfDay % 1000) {
    std::snprintf(buf, sizeof buf, ".%03lld", static_cast<long long>(frac));
    out += buf;
    while (out.back() == '0') out.pop_back();
  }
  return out;
}

std::string formatDate(int64_t seconds) { return "D#" + dateText(seconds); }
std::string formatTimeOfDay(int64_t ms) { return "TOD#" + clockText(ms); }
std::string formatDateAndTime(int64_t seconds) {
  int64_t secOfDay = ((seconds % 86400) + 86400) % 86400;
  return "DT#" + dateText(seconds) + "-" + clockText(secOfDay * 1000);
}

template <typename F>
static std::string formatFloat(F v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  std::string out(buf, res.ptr);
  if (out.find_first_of(".eEn") == std::string::npos) out += ".0";  // nan/inf contain 'n'
  for (auto& c : out)
    if (c == 'e') c = 'E';
  return out;
}

std::string formatReal(float v) { return formatFloat(v); }
std::string formatLreal(double v) { return formatFloat(v); }

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
