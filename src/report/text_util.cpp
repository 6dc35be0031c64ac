#include "report/text_util.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "core/iec_value.hpp"

namespace virtcom::report {

namespace {

const std::string kUnknown = "?";
constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// Length of the valid UTF-8 sequence starting at s[i], 0 if invalid (overlong forms, surrogates
// and code points above U+10FFFF are invalid too).
size_t utf8SequenceLength(std::string_view s, size_t i) {
  auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  unsigned char c = byte(i);
  if (c < 0x80) return 1;
  size_t len = 0;
  uint32_t cp = 0;
  if ((c & 0xE0) == 0xC0) { len = 2; cp = c & 0x1F; }
  else if ((c & 0xF0) == 0xE0) { len = 3; cp = c & 0x0F; }
  else if ((c & 0xF8) == 0xF0) { len = 4; cp = c & 0x07; }
  else return 0;
  if (i + len > s.size()) return 0;
  for (size_t k = 1; k < len; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  static constexpr uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return len;
}

}  // namespace

std::string formatFixed(double v, int decimals) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[400];
  auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  std::string out(buf, res.ptr);
  // -0.000 reads badly in a table.
  if (out.starts_with('-') && out.find_first_not_of("-0.") == std::string::npos) out.erase(0, 1);
  return out;
}

std::string formatSeconds(int64_t ns, int decimals) {
  // Integer arithmetic: exact for any ns, rounding half away from zero.
  decimals = std::clamp(decimals, 0, 9);
  uint64_t unit = 1, scale = 1;
  for (int i = 0; i < 9 - decimals; ++i) unit *= 10;
  for (int i = 0; i < decimals; ++i) scale *= 10;
  bool negative = ns < 0;
  uint64_t magnitude = negative ? 0 - static_cast<uint64_t>(ns) : static_cast<uint64_t>(ns);
  uint64_t q = magnitude / unit + (magnitude % unit >= (unit + 1) / 2 && unit > 1 ? 1 : 0);
  // Appends only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
  std::string out = negative && q != 0 ? "-" : "";
  out += std::to_string(q / scale);
  if (decimals > 0) {
    std::string frac = std::to_string(q % scale);
    out += '.';
    out.append(static_cast<size_t>(decimals) - frac.size(), '0');
    out += frac;
  }
  return out;
}

std::string formatShortest(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string sanitizeUtf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    size_t len = utf8SequenceLength(s, i);
    unsigned char c = static_cast<unsigned char>(s[i]);
    if (len == 0) {
      out += kReplacement;
      ++i;
    } else if (len == 1 && ((c < 0x20 && c != '\t') || c == 0x7F)) {
      out += kReplacement;
      ++i;
    } else {
      out.append(s.substr(i, len));
      i += len;
    }
  }
  return out;
}

std::string escapeHtml(std::string_view s) {
  std::string clean = sanitizeUtf8(s);
  std::string out;
  out.reserve(clean.size() + 8);
  for (char c : clean) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

size_t displayWidth(std::string_view s) {
  size_t n = 0;
  for (char c : s)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
}

std::string fitWidth(std::string_view s, size_t width, std::string_view cutMark) {
  std::string clean = sanitizeUtf8(s);
  if (displayWidth(clean) <= width) return clean;
  if (width == 0) return {};
  // Keep width-1 code points, then the cut mark.
  size_t kept = 0, i = 0;
  for (; i < clean.size(); ++i) {
    if ((static_cast<unsigned char>(clean[i]) & 0xC0) != 0x80) {
      if (kept == width - 1) break;
      ++kept;
    }
  }
  return clean.substr(0, i) + std::string(cutMark);
}

std::string padRight(std::string_view s, size_t width) {
  std::string out(s);
  size_t w = displayWidth(s);
  if (w < width) out.append(width - w, ' ');
  return out;
}

std::string padLeft(std::string_view s, size_t width) {
  size_t w = displayWidth(s);
  std::string out(w < width ? width - w : 0, ' ');
  out += s;
  return out;
}

const char* runEndKey(RunEnd e) {
  switch (e) {
    case RunEnd::Completed: return "completed";
    case RunEnd::TimeLimit: return "time_limit";
    case RunEnd::PlcFault: return "plc_fault";
    case RunEnd::DeviceError: return "device_error";
    case RunEnd::Collision: return "collision";
    case RunEnd::Interrupted: return "interrupted";
  }
  return "unknown";
}

const std::string& deviceName(const Trace& t, uint32_t device) {
  return device < t.devices.size() ? t.devices[device].name : kUnknown;
}

const std::string& labelName(const Trace& t, uint32_t label) {
  return label < t.labels.size() ? t.labels[label] : kUnknown;
}

int64_t activityEndNs(const Trace& t, const ActivityRecord& a) {
  int64_t end = a.endNs < 0 ? t.endNs : a.endNs;
  return end < a.startNs ? a.startNs : end;
}

std::vector<uint32_t> heldActivities(const Trace& t) {
  const ActivityLog& log = t.activities;
  std::vector<uint32_t> out;
  out.reserve(log.headEnd() + log.passed().size() + (log.size() - log.tailBegin()));
  for (size_t i = 0; i < log.headEnd(); ++i) out.push_back(static_cast<uint32_t>(i));
  for (const ActivityLog::Passed& p : log.passed()) out.push_back(p.index);
  for (size_t i = log.tailBegin(); i < log.size(); ++i) out.push_back(static_cast<uint32_t>(i));
  return out;
}

std::string signalText(ElemType type, uint64_t raw) {
  if (type == ElemType::Bool) return raw != 0 ? "1" : "0";
  if (isFloat(type)) return formatShortest(std::bit_cast<double>(raw));
  ElemKind kind = elemTypeInfo(type).kind;
  if (isZeroExtendedKind(kind)) return std::to_string(raw);
  if (kind == ElemKind::Text) return {};
  return std::to_string(static_cast<int64_t>(raw));
}

bool isPlottable(ElemType type) { return elemTypeInfo(type).kind != ElemKind::Text; }

std::string chartValueText(ElemType type, double value) {
  if (!std::isfinite(value)) return formatShortest(value);
  const ElemTypeInfo& info = elemTypeInfo(type);
  if (info.kind == ElemKind::Bits) {
    char text[32];
    std::snprintf(text, sizeof text, "16#%0*llX", static_cast<int>(info.sizeBytes * 2),
                  static_cast<unsigned long long>(std::max(value, 0.0)));
    return text;
  }
  if (type == ElemType::Time) return formatTimeMs(static_cast<int64_t>(std::llround(value)));
  if (type == ElemType::Ltime) return formatLtimeNs(static_cast<int64_t>(std::llround(value)));
  if (info.kind != ElemKind::Float) return formatShortest(value);
  const double magnitude = std::abs(value);
  if (magnitude != 0 && (magnitude < 1e-3 || magnitude >= 1e12)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
  }
  std::string text = formatFixed(value, 3);
  while (text.ends_with('0')) text.pop_back();
  if (text.ends_with('.')) text.pop_back();
  return text == "-0" ? "0" : text;
}

}  // namespace virtcom::report
