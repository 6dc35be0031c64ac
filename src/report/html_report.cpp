#include "report/html_report.hpp"

#include <algorithm>
#include <cmath>

#include "core/ascii.hpp"
#include "report/html_chart.hpp"
#include "report/html_page.hpp"
#include "report/html_writes.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

using html::LabelColors;

std::string px(double v) { return formatFixed(v, 1); }

// 17067.3 -> "17 067.3" with thin spaces, as engineering reports write large numbers.
std::string grouped(const std::string& number) {
  size_t start = number.starts_with('-') ? 1 : 0;
  size_t end = number.find('.');
  if (end == std::string::npos) end = number.size();
  std::string out = number.substr(0, start);
  for (size_t i = start; i < end; ++i) {
    if (i > start && (end - i) % 3 == 0) out += "\u2009";
    out += number[i];
  }
  return out + number.substr(end);
}

std::string energy(double j) { return grouped(formatFixed(j, 1)); }

// A device that recorded no energy has no energy model in the cell (no power parameters: an
// ideal axis, robot, ...): "n/a" says so, where "0.0" would claim it moved for free.
std::string deviceEnergy(double j) {
  return j == 0 ? "<span title=\"no energy model: the device entry gives no power parameters\">n/a</span>" : energy(j);
}

// "1 min 41 s" for times of a minute or more, as seed Figure 11 labels cycle times.
std::string minutesText(int64_t ns) {
  int64_t s = (ns + 500'000'000) / 1'000'000'000;
  if (s < 60) return {};
  std::string out = s >= 3600 ? std::to_string(s / 3600) + " h " : "";
  return out + std::to_string(s / 60 % 60) + " min " + std::to_string(s % 60) + " s";
}

const char* endClass(RunEnd e) {
  switch (e) {
    case RunEnd::Completed: return "ok";
    case RunEnd::TimeLimit:
    case RunEnd::Interrupted: return "warn";
    default: return "bad";
  }
}

bool isRobot(const DeviceInfo& d) { return iequalsAscii(d.type, "robot"); }

std::string card(const std::string& key, const std::string& value, const std::string& unit,
                 const std::string& detail, bool bad = false) {
  return std::string("<div class=\"card") + (bad ? " bad" : "") + "\"><div class=\"k\">" + key +
         "</div><div class=\"v\">" + value + (unit.empty() ? "" : "<small>" + unit + "</small>") +
         "</div><div class=\"d\">" + (detail.empty() ? "&#160;" : detail) + "</div></div>\n";
}

std::string cards(const Kpis& k) {
  std::string cycleDetail = k.cycleMeasured ? "measured " + formatSeconds(k.windowStartNs, 1) + "\u2013" +
                                                  formatSeconds(k.windowEndNs, 1) + " s"
                                            : "whole run (no cycle markers)";
  std::string minutes = minutesText(k.cycleTimeNs);
  if (!minutes.empty()) cycleDetail = minutes + " \u00b7 " + cycleDetail;
  std::string out = "<section class=\"cards\">\n";
  if (k.cyclesCompleted > 1) cycleDetail = "last of " + std::to_string(k.cyclesCompleted) + " \u00b7 " + cycleDetail;
  out += card("Cycle time", formatSeconds(k.cycleTimeNs, 2), "s", cycleDetail);
  // Large totals in kJ/MJ so the card stays one line; the device table keeps joules.
  double j = k.totalEnergyJ;
  if (std::abs(j) < 1e5) out += card("Total energy", energy(j), "J", "all devices, whole run");
  else if (std::abs(j) < 1e8) out += card("Total energy", energy(j / 1e3), "kJ", "all devices, whole run");
  else out += card("Total energy", energy(j / 1e6), "MJ", "all devices, whole run");
  out += card("Operations", std::to_string(k.operations), "", "in the measured window");
  out += card("Errors", std::to_string(k.errors), "", "activities ended in error", k.errors > 0);
  out += card("Collisions", std::to_string(k.collisions), "", "", k.collisions > 0);
  out += card("Faults", std::to_string(k.faults), "", "", k.faults > 0);
  out += card("Cycles", std::to_string(k.cyclesCompleted), "",
              "run " + formatSeconds(k.runNs, 2) + " s");
  return out + "</section>\n";
}

std::string legend(const Trace& trace, const Kpis& k, const LabelColors& colors) {
  std::string out = "<ul class=\"legend\">";
  for (uint32_t label : colors.usedLabels())
    out += "<li><span class=\"sw\" style=\"background:" + html::hex(colors.color(label)) + "\"></span>" +
           escapeHtml(trace.labels[label]) + "</li>";
  if (colors.usedLabels().empty()) out += "<li>no activities recorded</li>";
  out += "<li class=\"sep\"></li>";
  bool running = std::any_of(k.devices.begin(), k.devices.end(), [](const DeviceKpis& d) { return d.running > 0; });
  if (k.errors > 0) out += "<li><span class=\"sw err\"></span>ended in error</li>";
  if (running) out += "<li><span class=\"sw run\"></span>running at end of run</li>";
  if (k.collisions > 0) out += "<li><span class=\"sw col\"></span>collision</li>";
  if (k.faults > 0) out += "<li><span class=\"sw flt\"></span>fault</li>";
  if (k.cycleMeasured) out += "<li><span class=\"sw cyc\"></span>measured cycle</li>";
  return out + "</ul>\n";
}

std::string deviceTable(const Trace& trace, const Kpis& k) {
  std::string out =
      "<table><thead><tr><th class=\"l\">Device</th><th class=\"l\">Type</th><th>Busy s</th><th>Idle s</th>"
      "<th>Utilisation</th><th>Energy J</th><th>Ops</th><th>Errors</th></tr></thead><tbody>\n";
  for (const DeviceKpis& d : k.devices) {
    if (d.device >= trace.devices.size()) continue;
    const DeviceInfo& info = trace.devices[d.device];
    double pct = std::clamp(d.utilisationPct, 0.0, 100.0);
    out += "<tr><td class=\"l\">" + escapeHtml(info.name) + "</td><td class=\"l\">" + escapeHtml(info.type) +
           "</td><td>" + formatSeconds(d.busyNs, 3) + "</td><td>" + formatSeconds(d.idleNs, 3) +
           "</td><td><div class=\"util\"><div class=\"track\"><div class=\"fill\" style=\"width:" +
           formatFixed(pct, 1) + "%\"></div></div>" + formatFixed(d.utilisationPct, 1) + " %</div></td><td>" +
           deviceEnergy(d.energyJ) + "</td><td>" + std::to_string(d.operations) + "</td><td" +
           (d.errors ? " class=\"bad\"" : "") + ">" + std::to_string(d.errors) + "</td></tr>\n";
  }
  out += "<tr class=\"total\"><td class=\"l\">Total</td><td></td><td></td><td></td><td></td><td>" +
         energy(k.totalEnergyJ) + "</td><td>" + std::to_string(k.operations) + "</td><td" +
         (k.errors ? " class=\"bad\"" : "") + ">" + std::to_string(k.errors) + "</td></tr>\n";
  return out + "</tbody></table>\n";
}

// Horizontal bars of energy per robot (every device with energy when there are no robots).
std::string energyChart(const Trace& trace, const Kpis& k, std::string& heading) {
  std::vector<const DeviceKpis*> rows;
  for (const DeviceKpis& d : k.devices)
    if (d.device < trace.devices.size() && isRobot(trace.devices[d.device])) rows.push_back(&d);
  heading = "Energy per robot";
  if (rows.empty()) {
    heading = "Energy per device";
    for (const DeviceKpis& d : k.devices)
      if (d.device < trace.devices.size() && d.energyJ != 0) rows.push_back(&d);
  }
  if (rows.empty()) return "<p class=\"note\">No energy recorded.</p>\n";
  double maxJ = 0;
  for (const DeviceKpis* d : rows) maxJ = std::max(maxJ, d->energyJ);
  constexpr double kWidth = 460, kName = 120, kValue = 92, kRow = 34;
  double barMax = kWidth - kName - kValue;
  double height = static_cast<double>(rows.size()) * kRow + 6;
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart energy\" viewBox=\"0 0 " +
                    px(kWidth) + " " + px(height) + "\" width=\"" + px(kWidth) + "\" height=\"" + px(height) +
                    "\" role=\"img\" aria-label=\"" + heading + "\">\n";
  double y = 6;
  for (const DeviceKpis* d : rows) {
    const std::string& name = trace.devices[d->device].name;
    double w = maxJ > 0 ? std::max(0.0, d->energyJ) / maxJ * barMax : 0;
    out += "<text class=\"lane\" x=\"0\" y=\"" + px(y + 17) + "\">" + escapeHtml(fitWidth(name, 16, "\u2026")) +
           "<title>" + escapeHtml(name) + "</title></text><rect class=\"track-bg\" x=\"" + px(kName) + "\" y=\"" +
           px(y + 4) + "\" width=\"" + px(barMax) + "\" height=\"18\" rx=\"3\" fill=\"#eef1f4\"/><rect class=\"ebar\" x=\"" +
           px(kName) + "\" y=\"" + px(y + 4) + "\" width=\"" + px(w) + "\" height=\"18\" rx=\"3\"/><text class=\"evalue\" x=\"" +
           px(kWidth) + "\" y=\"" + px(y + 17) + "\" text-anchor=\"end\">" + (d->energyJ == 0 ? "n/a" : energy(d->energyJ) + " J") +
           "</text>\n";
    y += kRow;
  }
  return out + "</svg>\n";
}

// Every cycle of a run of several, so the "Cycle time" card (the last one) is not read as the
// mean; the table scrolls inside its panel. A long run shows its first and last kEdgeRows cycles
// (the page stays bounded by the chart width, not the run length; the JSON report lists all).
std::string cycleTable(const Trace& trace, const Kpis& k) {
  constexpr size_t kEdgeRows = 100;
  if (trace.cycles.size() < 2) return {};
  std::string out = "<section class=\"panel\" id=\"cycles\"><h2>Cycles<span class=\"hint\">" +
                    std::to_string(trace.cycles.size()) + " cycles \u00b7 min " + formatSeconds(k.cycleMinNs, 3) +
                    " s \u00b7 mean " + formatSeconds(static_cast<int64_t>(k.cycleMeanNs + 0.5), 3) + " s \u00b7 max " +
                    formatSeconds(k.cycleMaxNs, 3) + " s \u00b7 the Cycle time card is the last cycle; cycle 1 "
                    "includes the start-up</span></h2>\n<div class=\"scroll\"><table><thead><tr><th>Cycle</th>"
                    "<th>Start s</th><th>End s</th><th>Time s</th></tr></thead><tbody>\n";
  // A run longer than the trace's window kept only its first and last cycles (docs/report.md).
  const size_t n = trace.cycles.size();
  size_t head = n, tail = n;  // the rows shown: [0, head) and [tail, n)
  if (trace.cycles.elided() > 0) {
    head = std::min(kEdgeRows, trace.cycles.headEnd());
    tail = std::max(n - std::min(kEdgeRows, n), trace.cycles.tailBegin());
  } else if (n > 2 * kEdgeRows) {
    head = kEdgeRows;
    tail = n - kEdgeRows;
  }
  for (size_t i = 0; i < n; ++i) {
    if (i == head && tail > head) {
      out += "<tr><td class=\"l\" colspan=\"4\">\u2026 " + std::to_string(tail - head) + " more cycles (" +
             (trace.cycles.elided() > 0 ? "the middle of a long run is not kept" : "all of them in the JSON report") +
             ")</td></tr>\n";
      i = tail;
    }
    const CycleRecord& c = trace.cycles[i];
    out += "<tr><td>" + std::to_string(i + 1) + "</td><td>" + formatSeconds(c.startNs, 3) + "</td><td>" +
           formatSeconds(c.endNs, 3) + "</td><td>" + formatSeconds(c.endNs - c.startNs, 3) + "</td></tr>\n";
  }
  return out + "</tbody></table></div></section>\n";
}

// Collisions and faults in one table, in time order.
std::string eventTable(const Trace& trace) {
  if (trace.collisions.empty() && trace.faults.empty()) return {};
  struct Row {
    int64_t timeNs;
    bool collision;
    std::string where, details;
  };
  std::vector<Row> rows;
  for (const CollisionRecord& c : trace.collisions)
    rows.push_back({c.timeNs, true, escapeHtml(labelName(trace, c.zone)),
                    "<b>" + escapeHtml(deviceName(trace, c.deviceA)) + "</b> (" + escapeHtml(labelName(trace, c.activityA)) +
                        ") \u2194 <b>" + escapeHtml(deviceName(trace, c.deviceB)) + "</b> (" +
                        escapeHtml(labelName(trace, c.activityB)) + ")"});
  for (const FaultRecord& f : trace.faults)
    rows.push_back({f.timeNs, false, escapeHtml(f.source), escapeHtml(f.message)});
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.timeNs < b.timeNs; });
  std::string out = "<section class=\"panel\"><h2>Collisions and faults</h2>\n<table class=\"events\"><thead><tr>"
                    "<th>Time s</th><th class=\"l\">Event</th><th class=\"l\">Zone / source</th>"
                    "<th class=\"l\">Details</th></tr></thead><tbody>\n";
  for (const Row& r : rows)
    out += "<tr><td>" + formatSeconds(r.timeNs, 3) + "</td><td class=\"l\"><span class=\"tag " +
           (r.collision ? "col\">collision" : "flt\">fault") + "</span></td><td class=\"l\">" + r.where +
           "</td><td class=\"l wrap\">" + r.details + "</td></tr>\n";
  return out + "</tbody></table></section>\n";
}

}  // namespace

std::string htmlReport(const Trace& trace, const Kpis& kpis, const HtmlOptions& options) {
  std::string title = options.title.empty() ? "virtcom run" : options.title;
  html::TimeScale scale = html::makeTimeScale(trace, kpis, options.chartWidthPx, options.cycleOnly);
  LabelColors colors(trace);

  std::string out = htmlPageStart(title + " \u2014 virtcom run report");
  out += "<header><h1>" + escapeHtml(title) + "</h1><span class=\"pill " + endClass(kpis.end) + "\">" +
         escapeHtml(runEndName(kpis.end)) + "</span></header>\n<p class=\"subtitle\">";
  if (!options.subtitle.empty()) out += escapeHtml(options.subtitle) + " \u00b7 ";
  out += "virtcom run report \u00b7 " + std::to_string(trace.devices.size()) + " devices, " +
         std::to_string(trace.activities.size()) + " activities, " + std::to_string(trace.signals.size()) +
         " signals";
  if (trace.activities.elidedCount() > 0)
    out += " \u00b7 a long run: the chart shows its first and last activities";
  if (!kpis.endMessage.empty()) out += " \u00b7 " + escapeHtml(kpis.endMessage);
  // Writes into the PLC from outside (ADS, Modbus, OPC UA clients, the HMI's page): a reader of
  // the report must know the PLC did not run on its own (docs/security.md).
  if (trace.writesAudited) out += " \u00b7 " + externalWritesText(trace.externalWrites);
  out += "</p>\n";
  out += cards(kpis);

  out += "<section class=\"panel\"><h2>Activities<span class=\"hint\">one lane per device \u00b7 hover a bar "
         "for details</span></h2>\n";
  out += html::ganttSvg(trace, kpis, scale, colors);
  out += legend(trace, kpis, colors) + "</section>\n";

  std::string energyHeading;
  std::string energySvg = energyChart(trace, kpis, energyHeading);
  // Side by side while the device table fits beside the energy chart, else one below the other:
  // a fixed 3:2 grid made the table scroll sideways at 1400 px (issue 16).
  out += "<div class=\"two\"><section class=\"panel devices\"><h2>Devices<span class=\"hint\">busy and idle time "
         "within the measured window</span></h2>\n" + deviceTable(trace, kpis) +
         "</section><section class=\"panel energy\"><h2>" + energyHeading +
         "<span class=\"hint\">whole run, idle included</span></h2>\n" + energySvg + "</section></div>\n";
  out += cycleTable(trace, kpis);

  if (!options.signals.empty())
    out += "<section class=\"panel\"><h2>Signals</h2>\n" + html::signalsSvg(trace, kpis, scale, options) +
           "</section>\n";
  out += eventTable(trace);
  out += externalWritesHtml(trace);
  out += diagramTablesHtml(options.diagrams);
  out += "<footer>Generated by virtcom from the simulation trace. Times in seconds from the start of the run; "
         "energies in joules.</footer>\n";
  return out + kHtmlPageEnd;
}

}  // namespace virtcom::report
