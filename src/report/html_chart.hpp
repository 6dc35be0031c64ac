#pragma once
// Internal building blocks of the HTML report's SVG charts: the shared time scale and axis, the
// operation colour palette and the two charts. Not part of the public API.
#include <cstdint>
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "report/html_report.hpp"
#include "report/kpis.hpp"

namespace virtcom::report::html {

// Horizontal geometry shared by all time charts so their x positions line up.
inline constexpr double kLabelColumnPx = 190;
inline constexpr double kRightMarginPx = 28;
// Approximate advance of one character of the 11 px chart font (for fitting text into bars).
inline constexpr double kCharPx = 6.4;

struct TimeScale {
  int64_t startNs = 0, endNs = 1;
  double leftPx = 0, rightPx = 1;
  double widthPx = 0;  // whole SVG width
  double x(int64_t ns) const;
  // x clipped to the plot area.
  double clampedX(int64_t ns) const;
  // Whether [fromNs, toNs] is (partly) visible; a zero-length interval on an edge is.
  bool overlaps(int64_t fromNs, int64_t toNs) const {
    return fromNs == toNs ? fromNs >= startNs && fromNs <= endNs : fromNs < endNs && toNs > startNs;
  }
  bool contains(int64_t ns) const { return ns >= startNs && ns <= endNs; }
};

// The measured cycle when `cycleOnly` and the run has cycle markers; otherwise 0 .. the latest of
// run end, cycle end, activity ends and events. Never empty.
TimeScale makeTimeScale(const Trace& trace, const Kpis& kpis, int chartWidthPx, bool cycleOnly);

// Vertical grid lines at the axis ticks, from y `top` to `bottom`.
std::string timeGrid(const TimeScale& s, double top, double bottom);
// Axis line at y, tick marks, tick labels in seconds and the axis title below them (30 px).
std::string timeAxis(const TimeScale& s, double y);
// The measured cycle as a shaded band from `top` to `bottom`; empty if the run has no markers.
std::string cycleShade(const TimeScale& s, const Kpis& kpis, double top, double bottom);

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};
std::string hex(Rgb c);
// The i-th colour of the qualitative palette (operations, sweep series), generated beyond it.
Rgb paletteColor(size_t i);
// Black or white, whichever reads better on `c`.
const char* textColorOn(Rgb c);

// One colour per operation label used by an activity. Labels are ordered by name and take the
// palette in that order, so the same set of operations gets the same colours in every run
// (comparing sequence variants side by side).
class LabelColors {
 public:
  explicit LabelColors(const Trace& trace);
  Rgb color(uint32_t label) const;
  const std::vector<uint32_t>& usedLabels() const { return used_; }  // legend order

 private:
  std::vector<Rgb> byLabel_;
  std::vector<uint32_t> used_;
};

// Colours that mean something fixed in every chart.
inline constexpr const char* kErrorColor = "#d7263d";
inline constexpr const char* kFaultColor = "#e07b00";
inline constexpr const char* kMergedColor = "#9aa1ab";

// Lane group of a device: its `group` if set, else Robots / Press / Axes / Other by type.
std::string laneGroup(const DeviceInfo& d);

std::string ganttSvg(const Trace& trace, const Kpis& kpis, const TimeScale& scale,
                     const LabelColors& colors);
// Returns an empty string when `options.signals` is empty. Names not in the trace are listed
// under the chart.
std::string signalsSvg(const Trace& trace, const Kpis& kpis, const TimeScale& scale,
                       const HtmlOptions& options);

}  // namespace virtcom::report::html
