#include "report/waveform.hpp"

#include <bit>
#include <map>
#include <sstream>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

enum class VcdKind { Wire1, Real, Integer, Vector, None };

VcdKind vcdKind(ElemType t) {
  if (t == ElemType::Bool) return VcdKind::Wire1;
  if (isFloat(t)) return VcdKind::Real;
  switch (elemTypeInfo(t).kind) {
    case ElemKind::Bits:
    case ElemKind::Unsigned:
    case ElemKind::Char: return VcdKind::Vector;
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

void VcdWriter::begin(const Trace& trace) {
  trace_ = &trace;
  now_ = 0;
  std::string out = "$version virtcom $end\n$timescale 1 ns $end\n";
  ids_.assign(trace.signals.size(), {});
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
    ids_[i] = vcdId(next++);
    const char* type = kind == VcdKind::Wire1 ? "wire" : kind == VcdKind::Real ? "real"
                       : kind == VcdKind::Integer ? "integer" : "wire";
    uint32_t width = kind == VcdKind::Real ? 64 : bitWidth(s.type);
    size_t dot = s.name.find('.');
    std::string ref = vcdName(dot == std::string::npos ? s.name : s.name.substr(dot + 1));
    std::string decl = "$var " + std::string(type) + " " + std::to_string(width) + " " + ids_[i] +
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
    if (!ids_[i].empty()) out += vcdValue(trace.signals[i].type, trace.signals[i].initial, ids_[i]) + "\n";
  out += "$end\n";
  out_ << out;
}

void VcdWriter::change(const SignalChange& c) {
  if (c.tag >= ids_.size() || ids_[c.tag].empty() || c.timeNs < 0) return;
  if (c.timeNs > now_) {
    now_ = c.timeNs;
    out_ << '#' << now_ << '\n';
  }
  out_ << vcdValue(trace_->signals[c.tag].type, c.raw, ids_[c.tag]) << '\n';
}

void VcdWriter::end(const Trace& trace) {
  if (trace.endNs > now_) out_ << '#' << trace.endNs << '\n';
}

void CsvWriter::begin(const Trace& trace) {
  trace_ = &trace;
  out_ << "time_s,signal,value\n";
  names_.clear();
  names_.reserve(trace.signals.size());
  for (const SignalInfo& s : trace.signals) names_.push_back(csvField(s.name));
  for (size_t i = 0; i < trace.signals.size(); ++i) {
    const SignalInfo& s = trace.signals[i];
    if (isPlottable(s.type)) out_ << "0.000000000," << names_[i] << ',' << signalText(s.type, s.initial) << '\n';
  }
}

void CsvWriter::change(const SignalChange& c) {
  if (c.tag >= names_.size() || !isPlottable(trace_->signals[c.tag].type)) return;
  out_ << formatSeconds(c.timeNs, 9) << ',' << names_[c.tag] << ',' << signalText(trace_->signals[c.tag].type, c.raw) << '\n';
}

void replay(const Trace& trace, TraceSink& sink) {
  sink.begin(trace);
  for (const SignalChange& c : trace.changes) sink.change(c);
  sink.end(trace);
}

std::string vcdReport(const Trace& trace) {
  std::ostringstream out;
  VcdWriter writer(out);
  replay(trace, writer);
  return std::move(out).str();
}

std::string csvChanges(const Trace& trace) {
  std::ostringstream out;
  CsvWriter writer(out);
  replay(trace, writer);
  return std::move(out).str();
}

}  // namespace virtcom::report
