#include "report/waveform.hpp"

#include <bit>
#include <map>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

enum class VcdKind { Wire1, Real, Integer, Vector, None };

VcdKind vcdKind(ElemType t) {
  if (t == ElemType::Bool) return VcdKind::Wire1;
  if (isFloat(t)) return VcdKind::Real;
  switch (elemTypeInfo(t).kind) {
    case ElemKind::Bits:
    case ElemKind::Unsigned: return VcdKind::Vector;
    case ElemKind::Signed:
    case ElemKind::Duration:
    case ElemKind::Date: return VcdKind::Integer;
    default: return VcdKind::None;
  }
}

// Identifier codes: base-94 over the printable ASCII characters '!'..'~' (§18.2.1).
std::string vcdId(size_t index) {
  std::string id;
  do {
    id += static_cast<char>('!' + index % 94);
    index /= 94;
  } while (index);
  return id;
}

// VCD identifiers end at whitespace; anything outside printable ASCII becomes '_'.
std::string vcdName(std::string_view s) {
  std::string out;
  for (char c : s) out += (c > ' ' && c < 0x7F) ? c : '_';
  return out.empty() ? "_" : out;
}

std::string vcdValue(ElemType t, uint64_t raw, const std::string& id) {
  switch (vcdKind(t)) {
    case VcdKind::Wire1: return std::string(1, raw ? '1' : '0') += id;
    case VcdKind::Real: {
      std::string out = "r";
      out += formatShortest(std::bit_cast<double>(raw));
      out += ' ';
      return out += id;
    }
    case VcdKind::Integer:
    case VcdKind::Vector: {
      uint32_t width = bitWidth(t);
      uint64_t v = width >= 64 ? raw : raw & ((uint64_t(1) << width) - 1);
      // Shortest form; a negative signed value keeps its full width because VCD left-extends
      // vectors with 0.
      bool negative = vcdKind(t) == VcdKind::Integer && static_cast<int64_t>(raw) < 0;
      int top = negative ? static_cast<int>(width) - 1 : 63 - std::countl_zero(v | 1);
      std::string bits = "b";
      for (int b = top; b >= 0; --b) bits += ((v >> b) & 1) ? '1' : '0';
      return bits + " " + id;
    }
    case VcdKind::None: break;
  }
  return {};
}

std::string csvField(std::string_view s) {
  std::string clean = sanitizeUtf8(s);
  if (clean.find_first_of(",\"\n\r") == std::string::npos) return clean;
  std::string out = "\"";
  for (char c : clean) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string vcdReport(const Trace& trace) {
  std::string out = "$version virtcom $end\n$timescale 1 ns $end\n";
  std::vector<std::string> ids(trace.signals.size());
  std::string skipped;
  // Scope per prefix, in order of first appearance, each with its vars in signal order.
  std::vector<std::string> scopeOrder;
  std::map<std::string, std::string> scopeVars;
  std::string rootVars;
  size_t next = 0;
  for (size_t i = 0; i < trace.signals.size(); ++i) {
    const SignalInfo& s = trace.signals[i];
    VcdKind kind = vcdKind(s.type);
    if (kind == VcdKind::None) {
      skipped += ' ';
      skipped += vcdName(s.name);
      continue;
    }
    ids[i] = vcdId(next++);
    const char* type = kind == VcdKind::Wire1 ? "wire" : kind == VcdKind::Real ? "real"
                       : kind == VcdKind::Integer ? "integer" : "wire";
    uint32_t width = kind == VcdKind::Real ? 64 : bitWidth(s.type);
    size_t dot = s.name.find('.');
    std::string ref = vcdName(dot == std::string::npos ? s.name : s.name.substr(dot + 1));
    std::string decl = "$var " + std::string(type) + " " + std::to_string(width) + " " + ids[i] +
                       " " + ref + " $end\n";
    if (dot == std::string::npos || dot == 0) {
      rootVars += decl;
      continue;
    }
    std::string scope = vcdName(s.name.substr(0, dot));
    if (!scopeVars.contains(scope)) scopeOrder.push_back(scope);
    scopeVars[scope] += decl;
  }
  if (!skipped.empty()) out += "$comment not dumped (STRING/WSTRING):" + skipped + " $end\n";
  out += "$scope module virtcom $end\n" + rootVars;
  for (const std::string& scope : scopeOrder)
    out += "$scope module " + scope + " $end\n" + scopeVars[scope] + "$upscope $end\n";
  out += "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n";
  for (size_t i = 0; i < trace.signals.size(); ++i)
    if (!ids[i].empty()) out += vcdValue(trace.signals[i].type, trace.signals[i].initial, ids[i]) + "\n";
  out += "$end\n";
  int64_t now = 0;
  for (const SignalChange& c : trace.changes) {
    if (c.tag >= trace.signals.size() || ids[c.tag].empty() || c.timeNs < 0) continue;
    if (c.timeNs > now) {
      now = c.timeNs;
      out += '#';
      out += std::to_string(now);
      out += '\n';
    }
    out += vcdValue(trace.signals[c.tag].type, c.raw, ids[c.tag]) + "\n";
  }
  if (trace.endNs > now) {
    out += '#';
    out += std::to_string(trace.endNs);
    out += '\n';
  }
  return out;
}

std::string csvChanges(const Trace& trace) {
  std::string out = "time_s,signal,value\n";
  std::vector<std::string> names;
  names.reserve(trace.signals.size());
  for (const SignalInfo& s : trace.signals) names.push_back(csvField(s.name));
  for (size_t i = 0; i < trace.signals.size(); ++i) {
    const SignalInfo& s = trace.signals[i];
    if (isPlottable(s.type)) out += "0.000000000," + names[i] + "," + signalText(s.type, s.initial) + "\n";
  }
  for (const SignalChange& c : trace.changes) {
    if (c.tag >= trace.signals.size() || !isPlottable(trace.signals[c.tag].type)) continue;
    out += formatSeconds(c.timeNs, 9) + "," + names[c.tag] + "," +
           signalText(trace.signals[c.tag].type, c.raw) + "\n";
  }
  return out;
}

}  // namespace virtcom::report
