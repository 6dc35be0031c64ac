// The signal timeline of the HTML report: BOOL signals as digital waveforms, numbers as step
// plots, on the same time scale as the Gantt chart.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "report/html_chart.hpp"
#include "report/text_util.hpp"

namespace virtcom::report::html {

namespace {

constexpr double kTopPadPx = 8;
constexpr double kBoolLanePx = 30;
constexpr double kNumberLanePx = 58;
constexpr double kLanePadPx = 5;
constexpr size_t kNameChars = 24;

std::string px(double v) { return formatFixed(v, 1); }

struct Step {
  int64_t timeNs;
  double value;
};

struct Vertex {
  double x, value;
};

// Step-plot vertices with at most 4 per pixel column: a column with several changes becomes a
// vertical stroke over their min..max, so the output is bounded by the chart width.
std::vector<Vertex> stepVertices(double initial, const std::vector<Step>& steps, const TimeScale& s) {
  std::vector<Vertex> v;
  auto push = [&](double x, double value) {
    if (!v.empty() && v.back().x == x && v.back().value == value) return;
    v.push_back({x, value});
  };
  double cur = initial;
  push(s.leftPx, cur);
  for (size_t i = 0; i < steps.size();) {
    double col = std::floor(s.x(steps[i].timeNs));
    double prev = cur, lo = cur, hi = cur;
    size_t j = i;
    for (; j < steps.size() && std::floor(s.x(steps[j].timeNs)) == col; ++j) {
      lo = std::min(lo, steps[j].value);
      hi = std::max(hi, steps[j].value);
      cur = steps[j].value;
    }
    double x = j - i == 1 ? s.x(steps[i].timeNs) : col;
    push(x, prev);
    if (j - i > 1) {
      push(x, hi);
      push(x, lo);
    }
    push(x, cur);
    i = j;
  }
  push(s.rightPx, cur);
  return v;
}

struct Lane {
  TagId tag;
  bool isBool;
  double initial;
  std::vector<Step> steps;
};

}  // namespace

std::string signalsSvg(const Trace& trace, const Kpis& kpis, const TimeScale& s, const HtmlOptions& options) {
  if (options.signals.empty()) return {};
  std::unordered_map<std::string, TagId> byName;
  for (TagId i = 0; i < trace.signals.size(); ++i) byName.emplace(trace.signals[i].name, i);

  std::vector<Lane> lanes;
  std::vector<int> laneOfTag(trace.signals.size(), -1);
  std::string missing;
  for (const std::string& name : options.signals) {
    auto it = byName.find(name);
    if (it == byName.end() || !isPlottable(trace.signals[it->second].type)) {
      missing += (missing.empty() ? "" : ", ") + name;
      continue;
    }
    if (laneOfTag[it->second] >= 0) continue;
    laneOfTag[it->second] = static_cast<int>(lanes.size());
    const SignalInfo& info = trace.signals[it->second];
    lanes.push_back({it->second, info.type == ElemType::Bool, signalNumber(info.type, info.initial), {}});
  }
  for (const SignalChange& c : trace.changes) {
    if (c.tag >= laneOfTag.size() || laneOfTag[c.tag] < 0 || c.timeNs > s.endNs) continue;
    Lane& lane = lanes[static_cast<size_t>(laneOfTag[c.tag])];
    double value = signalNumber(trace.signals[c.tag].type, c.raw);
    if (c.timeNs <= s.startNs) lane.initial = value;  // value when the chart starts
    else lane.steps.push_back({c.timeNs, value});
  }

  std::string note;
  if (!missing.empty())
    note = "<p class=\"note\">Not in this trace or not plottable: " + escapeHtml(missing) + "</p>\n";
  if (lanes.empty()) return note;

  double height = kTopPadPx;
  for (const Lane& l : lanes) height += l.isBool ? kBoolLanePx : kNumberLanePx;
  const double lanesBottom = height;
  height += 40;

  std::string zebra, body;
  double y = kTopPadPx;
  for (size_t li = 0; li < lanes.size(); ++li) {
    const Lane& lane = lanes[li];
    const SignalInfo& info = trace.signals[lane.tag];
    double laneH = lane.isBool ? kBoolLanePx : kNumberLanePx;
    double initial = lane.initial;
    double lo = lane.isBool ? 0 : initial, hi = lane.isBool ? 1 : initial;
    for (const Step& st : lane.steps) {
      if (!std::isfinite(st.value)) continue;
      lo = std::min(lo, st.value);
      hi = std::max(hi, st.value);
    }
    if (!std::isfinite(lo) || !std::isfinite(hi)) lo = hi = 0;
    if (hi == lo) {
      hi += 1;
      // A flat WORD or UINT at 0 keeps 0 as its floor: there is no 16#FFFF below it.
      const ElemKind kind = elemTypeInfo(info.type).kind;
      const bool unsignedZero = (kind == ElemKind::Bits || kind == ElemKind::Unsigned) && lo == 0;
      lo -= lane.isBool || unsignedZero ? 0 : 1;
    }
    double top = y + kLanePadPx, bottom = y + laneH - kLanePadPx;
    auto yOf = [&](double v) {
      double f = std::isfinite(v) ? (v - lo) / (hi - lo) : 0;
      return bottom - std::clamp(f, 0.0, 1.0) * (bottom - top);
    };
    std::vector<Vertex> vertices = stepVertices(initial, lane.steps, s);
    std::string points;
    for (const Vertex& v : vertices) points += px(v.x) + "," + px(yOf(v.value)) + " ";
    std::string base = px(yOf(lo));
    if (li % 2 == 1)
      zebra += "<rect class=\"zebra\" x=\"0\" y=\"" + px(y) + "\" width=\"" + px(s.widthPx) + "\" height=\"" +
              px(laneH) + "\"/>";
    std::string kind = lane.isBool ? " bool" : "";
    body += "<polygon class=\"area" + kind + "\" points=\"" + px(s.leftPx) + "," + base + " " + points +
            px(s.rightPx) + "," + base + "\"/><polyline class=\"wave" + kind + "\" points=\"" + points + "\"/>";
    const char* typeName = elemTypeInfo(info.type).name.data();
    double mid = y + laneH / 2;
    body += "<text class=\"lane\" x=\"16\" y=\"" + px(lane.isBool ? mid + 4 : mid - 2) + "\">" +
            escapeHtml(fitWidth(info.name, kNameChars, "\u2026")) + "<title>" +
            escapeHtml(info.name + " : " + typeName) + "</title></text>";
    if (!lane.isBool)
      body += "<text class=\"sub\" x=\"16\" y=\"" + px(mid + 12) + "\">" + std::string(typeName) + "</text>";
    if (!lane.isBool)
      body += "<text class=\"range\" x=\"" + px(s.leftPx - 6) + "\" y=\"" + px(top + 4) +
            "\" text-anchor=\"end\">" + chartValueText(info.type, hi) + "</text><text class=\"range\" x=\"" +
            px(s.leftPx - 6) + "\" y=\"" + px(bottom + 3) + "\" text-anchor=\"end\">" + chartValueText(info.type, lo) +
            "</text>";
    body += "\n";
    y += laneH;
  }

  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart signals\" viewBox=\"0 0 " +
                    px(s.widthPx) + " " + px(height) + "\" width=\"" + px(s.widthPx) + "\" height=\"" +
                    px(height) + "\" role=\"img\" aria-label=\"Signal timeline\">\n";
  out += zebra;
  out += cycleShade(s, kpis, kTopPadPx, lanesBottom);
  out += timeGrid(s, kTopPadPx, lanesBottom);
  out += body;
  out += timeAxis(s, lanesBottom);
  return out + "</svg>\n" + note;
}

}  // namespace virtcom::report::html
