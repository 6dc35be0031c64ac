// The sweep page: KPI charts (heat maps for two parameters, KPI over each parameter otherwise)
// and the table of points, as one self-contained HTML file.
#include "report/sweep_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "report/html_chart.hpp"
#include "report/html_page.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

using html::Rgb;

struct Kpi {
  const char* title;
  const char* unit;
  int decimals;
  double (*value)(const SweepTable::Row&);
};
constexpr Kpi kKpis[] = {
    {"Cycle time", "s", 3, [](const SweepTable::Row& r) { return r.cycleS; }},
    {"Energy", "J", 1, [](const SweepTable::Row& r) { return r.energyJ; }},
};

// A parameter's axis: its distinct values in order (numbers ascending when every value starts
// with one, "900 mm/s" < "1150 mm/s"; otherwise as they first appear) and their positions.
struct Axis {
  std::vector<std::string> values;
  std::vector<double> at;  // 0..1 across the plot
  size_t index(const std::string& v) const { return static_cast<size_t>(std::find(values.begin(), values.end(), v) - values.begin()); }
};

bool leadingNumber(const std::string& text, double& v) {
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && std::isfinite(v);
}

Axis makeAxis(const SweepTable& t, size_t parameter) {
  Axis a;
  for (const SweepTable::Row& r : t.rows)
    if (std::ranges::find(a.values, r.values[parameter]) == a.values.end()) a.values.push_back(r.values[parameter]);
  std::vector<double> numbers(a.values.size());
  bool numeric = true;
  for (size_t i = 0; i < a.values.size(); ++i) numeric = numeric && leadingNumber(a.values[i], numbers[i]);
  if (numeric) {
    std::vector<size_t> order(a.values.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::ranges::stable_sort(order, {}, [&](size_t i) { return numbers[i]; });
    std::vector<std::string> sorted;
    for (size_t i : order) sorted.push_back(a.values[i]);
    a.values = std::move(sorted);
    std::ranges::sort(numbers);
    const double lo = numbers.front(), span = numbers.back() - numbers.front();
    for (double n : numbers) a.at.push_back(span > 0 ? (n - lo) / span : 0.5);
  } else {
    for (size_t i = 0; i < a.values.size(); ++i) a.at.push_back(a.values.size() > 1 ? static_cast<double>(i) / static_cast<double>(a.values.size() - 1) : 0.5);
  }
  return a;
}

// 1, 2 or 5 times a power of ten, giving about `ticks` steps over `span`.
double niceStep(double span, int ticks) {
  const double raw = span / ticks;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * mag >= raw) return m * mag;
  return 10 * mag;
}

struct Range {
  double lo = 0, hi = 1;
};

Range kpiRange(const SweepTable& t, const Kpi& k) {
  Range r{INFINITY, -INFINITY};
  for (const SweepTable::Row& row : t.rows)
    if (row.feasible) {
      r.lo = std::min(r.lo, k.value(row));
      r.hi = std::max(r.hi, k.value(row));
    }
  if (r.lo > r.hi) return {0, 1};
  if (r.hi - r.lo < 1e-9 * std::max(1.0, std::fabs(r.hi))) {
    r.lo -= 0.5;
    r.hi += 0.5;
  }
  return r;
}

std::string num(double v) { return formatFixed(v, 1); }

// What a point's tooltip says: its parameters and KPIs or why it failed.
std::string pointTitle(const SweepTable& t, const SweepTable::Row& r) {
  std::string s = "point " + std::to_string(r.point);
  for (size_t p = 0; p < t.parameters.size(); ++p) s += "\n" + t.parameters[p] + " = " + r.values[p];
  s += r.feasible ? "\ncycle " + formatFixed(r.cycleS, 3) + " s, energy " + formatFixed(r.energyJ, 1) + " J" : "\n" + r.result;
  return "<title>" + escapeHtml(s) + "</title>";
}

constexpr double kW = 620, kH = 300, kLeft = 70, kRight = 20, kTop = 16, kBottom = 52;

// The KPI over one parameter: a marker per point, a line per setting of the other parameters;
// failed points as red crosses on the x axis.
std::string lineChart(const SweepTable& t, size_t parameter, const Kpi& k) {
  const Axis axis = makeAxis(t, parameter);
  Range y = kpiRange(t, k);
  const double step = niceStep(y.hi - y.lo, 5);
  y.lo = std::floor(y.lo / step) * step;
  y.hi = std::ceil(y.hi / step) * step;
  const double plotW = kW - kLeft - kRight, plotH = kH - kTop - kBottom;
  auto px = [&](size_t v) { return kLeft + 10 + axis.at[v] * (plotW - 20); };
  auto py = [&](double v) { return kTop + plotH - (v - y.lo) / (y.hi - y.lo) * plotH; };
  std::string s = "<svg class=\"chart\" viewBox=\"0 0 " + num(kW) + " " + num(kH) + "\" width=\"" + num(kW) + "\" height=\"" + num(kH) + "\">\n<g class=\"grid\">";
  std::string labels;
  for (double v = y.lo; v <= y.hi + step / 2; v += step) {
    s += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(kW - kRight) + "\" y1=\"" + num(py(v)) + "\" y2=\"" + num(py(v)) + "\"/>";
    labels += "<text x=\"" + num(kLeft - 6) + "\" y=\"" + num(py(v) + 4) + "\" text-anchor=\"end\">" + formatShortest(std::round(v / step) * step) + "</text>";
  }
  s += "</g>\n<g class=\"axis\"><line x1=\"" + num(kLeft) + "\" x2=\"" + num(kW - kRight) + "\" y1=\"" + num(kTop + plotH) + "\" y2=\"" + num(kTop + plotH) + "\"/></g>\n" + labels;
  for (size_t v = 0; v < axis.values.size(); ++v)
    s += "<text x=\"" + num(px(v)) + "\" y=\"" + num(kTop + plotH + 16) + "\" text-anchor=\"middle\">" + escapeHtml(axis.values[v]) + "</text>";
  s += "<text x=\"" + num(kLeft + plotW / 2) + "\" y=\"" + num(kH - 10) + "\" text-anchor=\"middle\" class=\"lane\">" + escapeHtml(t.parameters[parameter]) + "</text>";
  s += "<text transform=\"translate(14 " + num(kTop + plotH / 2) + ") rotate(-90)\" text-anchor=\"middle\" class=\"lane\">" + k.title + " [" + k.unit + "]</text>\n";
  // Series: the rows that agree on every other parameter.
  std::map<std::string, std::vector<const SweepTable::Row*>> series;
  std::vector<std::string> seriesOrder;
  for (const SweepTable::Row& r : t.rows) {
    std::string key;
    for (size_t p = 0; p < t.parameters.size(); ++p)
      if (p != parameter) key += (key.empty() ? "" : ", ") + t.parameters[p] + " = " + r.values[p];
    if (!series.contains(key)) seriesOrder.push_back(key);
    series[key].push_back(&r);
  }
  const bool lines = seriesOrder.size() <= 12;
  std::string legend;
  for (size_t i = 0; i < seriesOrder.size(); ++i) {
    const std::string color = html::hex(lines ? html::paletteColor(i) : html::paletteColor(0));
    std::vector<const SweepTable::Row*> rows = series[seriesOrder[i]];
    std::ranges::stable_sort(rows, {}, [&](const SweepTable::Row* r) { return axis.index(r->values[parameter]); });
    std::string path;
    for (const SweepTable::Row* r : rows)
      if (r->feasible) path += (path.empty() ? "M" : " L") + num(px(axis.index(r->values[parameter]))) + " " + num(py(k.value(*r)));
    if (lines && rows.size() > 1) s += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + color + "\" stroke-width=\"1.6\"/>";
    for (const SweepTable::Row* r : rows) {
      const double x = px(axis.index(r->values[parameter]));
      if (r->feasible)
        s += "<circle cx=\"" + num(x) + "\" cy=\"" + num(py(k.value(*r))) + "\" r=\"4\" fill=\"" + color + "\">" + pointTitle(t, *r) + "</circle>";
      else
        s += "<path class=\"failed\" d=\"M" + num(x - 4) + " " + num(kTop + plotH - 4) + " l8 8 m0 -8 l-8 8\" stroke=\"" + html::kErrorColor +
             "\" stroke-width=\"2\">" + pointTitle(t, *r) + "</path>";
    }
    if (lines && !seriesOrder[i].empty())
      legend += "<li><span class=\"sw\" style=\"background:" + color + "\"></span>" + escapeHtml(seriesOrder[i]) + "</li>";
  }
  s += "\n</svg>\n";
  if (!legend.empty()) s += "<ul class=\"legend\">" + legend + "</ul>\n";
  return s;
}

// Sequential blue scale, light (low) to dark (high).
std::string shade(double f) {
  const Rgb lo{0xde, 0xeb, 0xf7}, hi{0x08, 0x30, 0x6b};
  auto mix = [&](uint8_t a, uint8_t b) { return static_cast<uint8_t>(std::lround(a + (b - a) * f)); };
  return html::hex({mix(lo.r, hi.r), mix(lo.g, hi.g), mix(lo.b, hi.b)});
}

// Two parameters: a cell per pair of values coloured by the KPI (the first point of a pair when
// random sampling drew it twice), failed pairs marked with a red cross.
std::string heatMap(const SweepTable& t, const Kpi& k) {
  const Axis xs = makeAxis(t, 0), ys = makeAxis(t, 1);
  const Range range = kpiRange(t, k);
  const double left = 110, top = 10, cellW = std::min(90.0, 500.0 / static_cast<double>(xs.values.size())), cellH = 30;
  const double w = left + cellW * static_cast<double>(xs.values.size()) + 20, h = top + cellH * static_cast<double>(ys.values.size()) + 60;
  std::vector<const SweepTable::Row*> cells(xs.values.size() * ys.values.size(), nullptr);
  for (const SweepTable::Row& r : t.rows) {
    const SweepTable::Row*& c = cells[ys.index(r.values[1]) * xs.values.size() + xs.index(r.values[0])];
    if (!c) c = &r;
  }
  std::string s = "<svg class=\"chart\" viewBox=\"0 0 " + num(w) + " " + num(h) + "\" width=\"" + num(w) + "\" height=\"" + num(h) + "\">\n";
  for (size_t yi = 0; yi < ys.values.size(); ++yi) {
    const double y = top + cellH * static_cast<double>(ys.values.size() - 1 - yi);
    s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(y + cellH / 2 + 4) + "\" text-anchor=\"end\">" + escapeHtml(ys.values[yi]) + "</text>";
    for (size_t xi = 0; xi < xs.values.size(); ++xi) {
      const SweepTable::Row* r = cells[yi * xs.values.size() + xi];
      if (!r) continue;
      const double x = left + cellW * static_cast<double>(xi);
      const double f = r->feasible ? (k.value(*r) - range.lo) / (range.hi - range.lo) : 0;
      s += "<g><rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(cellW - 1) + "\" height=\"" + num(cellH - 1) + "\" fill=\"" +
           (r->feasible ? shade(f) : std::string("#f6f8fa")) + "\"/>";
      const std::string text = r->feasible ? formatFixed(k.value(*r), k.decimals) : "\u2715";
      s += "<text x=\"" + num(x + cellW / 2) + "\" y=\"" + num(y + cellH / 2 + 4) + "\" text-anchor=\"middle\" style=\"fill:" +
           (r->feasible ? (f > 0.5 ? "#fff" : "#1f2328") : html::kErrorColor) + "\">" + text + "</text>" + pointTitle(t, *r) + "</g>";
    }
  }
  const double axisY = top + cellH * static_cast<double>(ys.values.size());
  for (size_t xi = 0; xi < xs.values.size(); ++xi)
    s += "<text x=\"" + num(left + cellW * (static_cast<double>(xi) + 0.5)) + "\" y=\"" + num(axisY + 16) + "\" text-anchor=\"middle\">" + escapeHtml(xs.values[xi]) + "</text>";
  s += "<text x=\"" + num(left + cellW * static_cast<double>(xs.values.size()) / 2) + "\" y=\"" + num(axisY + 40) + "\" text-anchor=\"middle\" class=\"lane\">" +
       escapeHtml(t.parameters[0]) + "</text>";
  s += "<text x=\"4\" y=\"" + num(top - 0) + "\" class=\"lane\" dominant-baseline=\"hanging\">" + escapeHtml(t.parameters[1]) + "</text>\n</svg>\n";
  s += "<ul class=\"legend\"><li><span class=\"sw\" style=\"background:" + shade(0) + "\"></span>" + formatFixed(range.lo, k.decimals) + " " + k.unit +
       "</li><li><span class=\"sw\" style=\"background:" + shade(1) + "\"></span>" + formatFixed(range.hi, k.decimals) + " " + k.unit + "</li></ul>\n";
  return s;
}

std::string pointsTable(const SweepTable& t) {
  std::string s = "<table><thead><tr><th>point</th>";
  for (const std::string& p : t.parameters) s += "<th>" + escapeHtml(p) + "</th>";
  s += "<th>cycle [s]</th><th>energy [J]</th><th>result</th></tr></thead><tbody>\n";
  for (const SweepTable::Row& r : t.rows) {
    s += "<tr><td>" + std::to_string(r.point) + "</td>";
    for (const std::string& v : r.values) s += "<td>" + escapeHtml(v) + "</td>";
    if (r.feasible) s += "<td>" + formatFixed(r.cycleS, 3) + "</td><td>" + formatFixed(r.energyJ, 1) + "</td><td>ok</td>";
    else s += "<td></td><td></td><td class=\"bad\">" + escapeHtml(r.result) + "</td>";
    s += "</tr>\n";
  }
  return s + "</tbody></table>\n";
}

}  // namespace

std::string sweepHtml(const SweepTable& t) {
  std::string s = htmlPageStart("Sweep " + t.title);
  size_t failed = 0;
  for (const SweepTable::Row& r : t.rows) failed += r.feasible ? 0 : 1;
  s += "<header><h1>Sweep " + escapeHtml(t.title) + "</h1></header>\n<p class=\"subtitle\">" + std::to_string(t.rows.size()) + " points, " +
       std::to_string(failed) + " failed</p>\n";
  if (!t.rows.empty())
    for (const Kpi& k : kKpis) {
      if (t.parameters.size() == 2) {
        s += "<section class=\"panel\"><h2>" + std::string(k.title) + " [" + k.unit + "]<span class=\"hint\">" + escapeHtml(t.parameters[0]) + " \u00d7 " +
             escapeHtml(t.parameters[1]) + "</span></h2>\n" + heatMap(t, k) + "</section>\n";
        continue;
      }
      for (size_t p = 0; p < t.parameters.size(); ++p)
        s += "<section class=\"panel\"><h2>" + std::string(k.title) + " over " + escapeHtml(t.parameters[p]) + "</h2>\n" + lineChart(t, p, k) + "</section>\n";
    }
  s += "<section class=\"panel\"><h2>Points</h2>\n" + pointsTable(t) + "</section>\n";
  return s + kHtmlPageEnd;
}

}  // namespace virtcom::report
