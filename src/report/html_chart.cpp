#include "report/html_chart.hpp"

#include <algorithm>
#include <cmath>

#include "core/ascii.hpp"
#include "report/text_util.hpp"

namespace virtcom::report::html {

namespace {

// Qualitative palette (Tableau 20 order without its reds, which mean "error" here): dark tones
// first so a few operations get clearly distinct colours.
constexpr Rgb kPalette[] = {
    {0x4e, 0x79, 0xa7}, {0xf2, 0x8e, 0x2b}, {0x59, 0xa1, 0x4f}, {0xb0, 0x7a, 0xa1},
    {0xed, 0xc9, 0x48}, {0x76, 0xb7, 0xb2}, {0x9c, 0x75, 0x5f}, {0xff, 0x9d, 0xa7},
    {0xa0, 0xcb, 0xe8}, {0xff, 0xbe, 0x7d}, {0x8c, 0xd1, 0x7d}, {0xd4, 0xa6, 0xc8},
    {0x49, 0x98, 0x94}, {0xf1, 0xce, 0x63}, {0xd7, 0xb5, 0xa6}, {0x79, 0x70, 0x6e},
};
constexpr size_t kPaletteSize = sizeof kPalette / sizeof kPalette[0];

// Beyond the palette: hues spaced by the golden angle, medium saturation and lightness.
Rgb generatedColor(size_t i) {
  double h = std::fmod(static_cast<double>(i) * 137.508, 360.0) / 60.0;
  double s = 0.55, l = 0.58;
  double c = (1 - std::fabs(2 * l - 1)) * s;
  double x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1));
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0: r = c; g = x; break;
    case 1: r = x; g = c; break;
    case 2: g = c; b = x; break;
    case 3: g = x; b = c; break;
    case 4: r = x; b = c; break;
    default: r = c; b = x; break;
  }
  double m = l - c / 2;
  auto channel = [&](double v) { return static_cast<uint8_t>(std::lround((v + m) * 255)); };
  return {channel(r), channel(g), channel(b)};
}

int64_t tickStepNs(int64_t spanNs, double plotPx) {
  double target = std::max(2.0, plotPx / 95.0);
  double raw = static_cast<double>(spanNs) / target;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag * 10;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  return std::max<int64_t>(1, std::llround(step));
}

// The first multiple of `step` at or after `startNs`.
int64_t firstTick(int64_t startNs, int64_t step) {
  int64_t q = startNs / step;
  if (q * step < startNs) ++q;
  return q * step;
}

int tickDecimals(int64_t stepNs) {
  int64_t unit = 1'000'000'000;
  for (int d = 0; d < 9; ++d, unit /= 10)
    if (stepNs % unit == 0) return d;
  return 9;
}

}  // namespace

Rgb paletteColor(size_t i) { return i < kPaletteSize ? kPalette[i] : generatedColor(i); }

double TimeScale::x(int64_t ns) const {
  double f = static_cast<double>(ns - startNs) / static_cast<double>(endNs - startNs);
  return leftPx + f * (rightPx - leftPx);
}

double TimeScale::clampedX(int64_t ns) const { return std::clamp(x(ns), leftPx, rightPx); }

TimeScale makeTimeScale(const Trace& trace, const Kpis& kpis, int chartWidthPx, bool cycleOnly) {
  TimeScale s;
  s.widthPx = std::clamp(chartWidthPx, 640, 4000);
  s.leftPx = kLabelColumnPx;
  s.rightPx = s.widthPx - kRightMarginPx;
  if (cycleOnly && kpis.cycleMeasured) {
    s.startNs = kpis.windowStartNs;
    s.endNs = kpis.windowEndNs;
    return s;
  }
  int64_t end = std::max({trace.endNs, kpis.windowEndNs, int64_t{0}});
  for (uint32_t i : heldActivities(trace)) end = std::max(end, activityEndNs(trace, trace.activities[i]));
  for (const CollisionRecord& c : trace.collisions) end = std::max(end, c.timeNs);
  for (const FaultRecord& f : trace.faults) end = std::max(end, f.timeNs);
  if (!trace.changes.empty()) end = std::max(end, trace.changes.back().timeNs);
  s.endNs = end > 0 ? end : 1'000'000'000;
  return s;
}

std::string timeGrid(const TimeScale& s, double top, double bottom) {
  int64_t step = tickStepNs(s.endNs - s.startNs, s.rightPx - s.leftPx);
  std::string out = "<g class=\"grid\">";
  for (int64_t t = firstTick(s.startNs, step); t <= s.endNs; t += step) {
    std::string x = formatFixed(s.x(t), 1);
    out += "<line x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" + formatFixed(top, 1) + "\" y2=\"" +
           formatFixed(bottom, 1) + "\"/>";
  }
  return out + "</g>\n";
}

std::string timeAxis(const TimeScale& s, double y) {
  int64_t step = tickStepNs(s.endNs - s.startNs, s.rightPx - s.leftPx);
  int decimals = tickDecimals(step);
  std::string ys = formatFixed(y, 1);
  std::string out = "<g class=\"axis\"><line x1=\"" + formatFixed(s.leftPx, 1) + "\" x2=\"" +
                    formatFixed(s.rightPx, 1) + "\" y1=\"" + ys + "\" y2=\"" + ys + "\"/>";
  for (int64_t t = firstTick(s.startNs, step); t <= s.endNs; t += step) {
    std::string x = formatFixed(s.x(t), 1);
    out += "<line x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" + ys + "\" y2=\"" + formatFixed(y + 5, 1) +
           "\"/><text x=\"" + x + "\" y=\"" + formatFixed(y + 17, 1) + "\" text-anchor=\"middle\">" +
           formatSeconds(t, decimals) + "</text>";
  }
  out += "<text class=\"axis-title\" x=\"" + formatFixed((s.leftPx + s.rightPx) / 2, 1) + "\" y=\"" +
         formatFixed(y + 31, 1) + "\" text-anchor=\"middle\">time [s]</text></g>\n";
  return out;
}

std::string cycleShade(const TimeScale& s, const Kpis& kpis, double top, double bottom) {
  if (!kpis.cycleMeasured) return {};
  std::string x0 = formatFixed(s.x(kpis.windowStartNs), 1), x1 = formatFixed(s.x(kpis.windowEndNs), 1);
  std::string t = formatFixed(top, 1), b = formatFixed(bottom, 1);
  return "<g class=\"cycle\"><rect x=\"" + x0 + "\" y=\"" + t + "\" width=\"" +
         formatFixed(s.x(kpis.windowEndNs) - s.x(kpis.windowStartNs), 1) + "\" height=\"" +
         formatFixed(bottom - top, 1) + "\"/><line x1=\"" + x0 + "\" x2=\"" + x0 + "\" y1=\"" + t +
         "\" y2=\"" + b + "\"/><line x1=\"" + x1 + "\" x2=\"" + x1 + "\" y1=\"" + t + "\" y2=\"" + b +
         "\"/></g>\n";
}

std::string hex(Rgb c) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "#";
  for (uint8_t v : {c.r, c.g, c.b}) {
    out += kDigits[v >> 4];
    out += kDigits[v & 15];
  }
  return out;
}

const char* textColorOn(Rgb c) {
  // WCAG relative luminance, approximated with gamma 2.2.
  auto lin = [](uint8_t v) { return std::pow(v / 255.0, 2.2); };
  double lum = 0.2126 * lin(c.r) + 0.7152 * lin(c.g) + 0.0722 * lin(c.b);
  return lum > 0.28 ? "#1f2328" : "#ffffff";
}

LabelColors::LabelColors(const Trace& trace) : byLabel_(trace.labels.size()) {
  std::vector<bool> seen(trace.labels.size());
  for (uint32_t i : heldActivities(trace))
    if (const ActivityRecord& a = trace.activities[i]; a.label < seen.size() && !seen[a.label]) {
      seen[a.label] = true;
      used_.push_back(a.label);
    }
  std::sort(used_.begin(), used_.end(), [&](uint32_t a, uint32_t b) {
    return trace.labels[a] != trace.labels[b] ? trace.labels[a] < trace.labels[b] : a < b;
  });
  for (size_t i = 0; i < used_.size(); ++i)
    byLabel_[used_[i]] = paletteColor(i);
}

Rgb LabelColors::color(uint32_t label) const {
  return label < byLabel_.size() ? byLabel_[label] : Rgb{0x9a, 0xa1, 0xab};
}

std::string laneGroup(const DeviceInfo& d) {
  if (!d.group.empty()) return d.group;
  if (iequalsAscii(d.type, "robot")) return "Robots";
  if (iequalsAscii(d.type, "press")) return "Press";
  if (iequalsAscii(d.type, "axis")) return "Axes";
  return "Other";
}

}  // namespace virtcom::report::html
