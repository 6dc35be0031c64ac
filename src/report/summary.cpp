#include "report/summary.hpp"

#include <algorithm>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

constexpr size_t kMaxNameWidth = 24;
constexpr size_t kMaxTypeWidth = 10;

struct Column {
  std::string title;
  size_t width;
  bool leftAligned;
};

std::string row(const std::vector<Column>& cols, const std::vector<std::string>& cells) {
  std::string line;
  for (size_t i = 0; i < cols.size(); ++i) {
    if (i) line += "  ";
    line += cols[i].leftAligned ? padRight(cells[i], cols[i].width) : padLeft(cells[i], cols[i].width);
  }
  while (line.ends_with(' ')) line.pop_back();
  return line + "\n";
}

std::string energyText(double j) { return formatFixed(j, 1); }

std::string deviceTable(const Trace& trace, const Kpis& kpis) {
  size_t nameWidth = 6, typeWidth = 4;
  for (const DeviceInfo& d : trace.devices) {
    nameWidth = std::max(nameWidth, std::min(kMaxNameWidth, displayWidth(sanitizeUtf8(d.name))));
    typeWidth = std::max(typeWidth, std::min(kMaxTypeWidth, displayWidth(sanitizeUtf8(d.type))));
  }
  std::vector<Column> cols = {{"Device", nameWidth, true}, {"Type", typeWidth, true},
                              {"Busy s", 9, false},        {"Idle s", 9, false},
                              {"Util %", 6, false},        {"Energy J", 10, false},
                              {"Ops", 5, false},           {"Errors", 6, false}};
  std::vector<std::string> titles, rules;
  for (const Column& c : cols) {
    titles.push_back(c.title);
    rules.push_back(std::string(c.width, '-'));
  }
  std::string out = row(cols, titles) + row(cols, rules);
  for (const DeviceKpis& d : kpis.devices) {
    const DeviceInfo* info = d.device < trace.devices.size() ? &trace.devices[d.device] : nullptr;
    out += row(cols, {fitWidth(info ? info->name : "?", nameWidth),
                      fitWidth(info ? info->type : "?", typeWidth), formatSeconds(d.busyNs, 3),
                      formatSeconds(d.idleNs, 3), formatFixed(d.utilisationPct, 1),
                      energyText(d.energyJ), std::to_string(d.operations), std::to_string(d.errors)});
  }
  out += row(cols, {"Total", "", "", "", "", energyText(kpis.totalEnergyJ),
                    std::to_string(kpis.operations), std::to_string(kpis.errors)});
  return out;
}

// Every cycle when there are several: which one "Cycle time" is must not be guessed. The
// terminal gets the first kMaxCycleRows; the JSON and HTML reports list them all.
constexpr size_t kMaxCycleRows = 20;

std::string cycleTable(const Trace& trace, const Kpis& kpis) {
  std::string out = "Cycles        min " + formatSeconds(kpis.cycleMinNs, 3) + " s, mean " +
                    formatSeconds(static_cast<int64_t>(kpis.cycleMeanNs + 0.5), 3) + " s, max " +
                    formatSeconds(kpis.cycleMaxNs, 3) + " s over " + std::to_string(trace.cycles.size()) +
                    " cycles (cycle 1 includes the start-up)\n";
  const std::vector<Column> cols = {{"Cycle", 7, false}, {"Start s", 11, false}, {"End s", 11, false}, {"Time s", 11, false}};
  out += "  " + row(cols, {"Cycle", "Start s", "End s", "Time s"});
  const size_t shown = std::min({trace.cycles.size(), kMaxCycleRows, trace.cycles.headEnd()});
  for (size_t i = 0; i < shown; ++i) {
    const CycleRecord& c = trace.cycles[i];
    out += "  " + row(cols, {std::to_string(i + 1), formatSeconds(c.startNs, 3), formatSeconds(c.endNs, 3),
                             formatSeconds(c.endNs - c.startNs, 3)});
  }
  if (trace.cycles.size() > shown)
    out += "  ... " + std::to_string(trace.cycles.size() - shown) +
           (trace.cycles.elided() > 0 ? " more (the first and last in --json and --report)\n"
                                      : " more (all of them in --json and --report)\n");
  return out;
}

}  // namespace

std::string summaryTable(const Trace& trace, const Kpis& kpis) {
  std::string out = deviceTable(trace, kpis);
  out += "\n";
  out += "Cycle time    " + formatSeconds(kpis.cycleTimeNs, 3) + " s";
  if (kpis.cycleMeasured)
    out += " (measured cycle " + formatSeconds(kpis.windowStartNs, 3) + " s .. " +
           formatSeconds(kpis.windowEndNs, 3) + " s, " + std::to_string(kpis.cyclesCompleted) +
           (kpis.cyclesCompleted == 1 ? " cycle" : " cycles") + " completed)\n";
  else
    out += " (whole run, no cycle markers)\n";
  if (trace.cycles.size() > 1) out += cycleTable(trace, kpis);
  out += "Total energy  " + energyText(kpis.totalEnergyJ) + " J\n";
  out += "Run time      " + formatSeconds(kpis.runNs, 3) + " s\n";
  if (trace.time.ticksSkipped > 0)
    out += "Event time    " + std::to_string(trace.time.ticksSkipped) + " of " + std::to_string(trace.time.ticks) +
           " ticks skipped in " + std::to_string(trace.time.jumps) + " jumps\n";
  if (trace.time.paced)
    out += "Late ticks    " + lateTicksText(trace.time.lateTicks, trace.time.ticks, trace.time.maxLateNs) + "\n";

  out += "Collisions    " + std::to_string(trace.collisions.size()) + "\n";
  for (const CollisionRecord& c : trace.collisions) {
    out += "  " + padLeft(formatSeconds(c.timeNs, 3), 9) + " s  zone " +
           fitWidth(labelName(trace, c.zone), kMaxNameWidth) + ": " +
           fitWidth(deviceName(trace, c.deviceA), kMaxNameWidth) + " (" +
           fitWidth(labelName(trace, c.activityA), kMaxNameWidth) + ") <-> " +
           fitWidth(deviceName(trace, c.deviceB), kMaxNameWidth) + " (" +
           fitWidth(labelName(trace, c.activityB), kMaxNameWidth) + ")\n";
  }
  return out + runOutcome(trace, kpis);
}

std::string lateTicksText(uint64_t late, uint64_t ticks, int64_t maxLateNs) {
  const std::string of = " of " + std::to_string(ticks) + (ticks == 1 ? " tick" : " ticks") + " started late";
  if (late == 0) return "none" + of;
  return std::to_string(late) + of + " (at most " + formatFixed(static_cast<double>(maxLateNs) * 1e-6, 3) + " ms)";
}

std::string runOutcome(const Trace& trace, const Kpis& kpis) {
  std::string out = "Faults        " + std::to_string(trace.faults.size()) + "\n";
  for (const FaultRecord& f : trace.faults)
    out += "  " + padLeft(formatSeconds(f.timeNs, 3), 9) + " s  " +
           fitWidth(f.source, kMaxNameWidth) + ": " + sanitizeUtf8(f.message) + "\n";
  out += "Run ended     " + std::string(runEndName(kpis.end));
  if (!kpis.endMessage.empty()) out += ": " + sanitizeUtf8(kpis.endMessage);
  out += "\n";
  return out;
}

}  // namespace virtcom::report
