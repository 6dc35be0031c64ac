#include "report/json_report.hpp"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/ascii.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

using Json = nlohmann::ordered_json;

// Seconds from ns: exact to the nanosecond for any run shorter than ~104 days.
double seconds(int64_t ns) { return nsToSeconds(ns); }

Json runJson(const Trace& trace, const Kpis& k) {
  Json run{{"end", runEndKey(k.end)},
           {"end_text", runEndName(k.end)},
           {"end_message", k.endMessage},
           {"duration_s", seconds(k.runNs)},
           {"cycles_completed", k.cyclesCompleted}};
  // How the clock went, known only to the simulation that ran (a history export has no ticks).
  const TimeSteps& t = trace.time;
  if (t.ticks > 0) {
    run["time"] = Json{{"mode", t.eventDriven ? "event" : "tick"},
                       {"ticks", t.ticks},
                       {"ticks_skipped", t.ticksSkipped},
                       {"jumps", t.jumps}};
    if (t.paced) {
      run["time"]["late_ticks"] = t.lateTicks;
      run["time"]["max_late_s"] = seconds(t.maxLateNs);
    }
  }
  if (trace.writesAudited) {
    uint64_t total = 0;
    Json byProtocol;
    for (size_t p = 0; p < kWriteProtocolCount; ++p) {
      total += trace.externalWrites[p];
      byProtocol[std::string(writeProtocolName(static_cast<WriteProtocol>(p)))] = trace.externalWrites[p];
    }
    run["external_writes"] = Json{{"total", total}};
    run["external_writes"].update(byProtocol);
  }
  return run;
}

Json cycleJson(const Trace& trace, const Kpis& k) {
  Json all = Json::array();
  for (const CycleRecord& c : trace.cycles)
    all.push_back(Json{{"start_s", seconds(c.startNs)}, {"end_s", seconds(c.endNs)}, {"time_s", seconds(c.endNs - c.startNs)}});
  Json cycle{{"measured", k.cycleMeasured},
              {"start_s", seconds(k.windowStartNs)},
              {"end_s", seconds(k.windowEndNs)},
              {"time_s", seconds(k.cycleTimeNs)},
              {"min_s", seconds(k.cycleMinNs)},
              {"mean_s", seconds(std::llround(k.cycleMeanNs))},  // whole ns: 94.6, not 94.60000000000001
              {"max_s", seconds(k.cycleMaxNs)},
              {"cycles", all}};
  // A long run lists its first and last cycles: which ones are missing is said, never guessed.
  if (trace.cycles.elided() > 0)
    cycle["cycles_elided"] = Json{{"count", trace.cycles.elided()}, {"after_cycle", trace.cycles.headEnd()}};
  return cycle;
}

Json devicesJson(const Trace& trace, const Kpis& k) {
  Json out = Json::array();
  for (const DeviceKpis& d : k.devices) {
    const DeviceInfo* info = d.device < trace.devices.size() ? &trace.devices[d.device] : nullptr;
    out.push_back(Json{{"index", d.device},
                       {"name", info ? info->name : "?"},
                       {"type", info ? info->type : "?"},
                       {"group", info ? info->group : ""},
                       {"busy_s", seconds(d.busyNs)},
                       {"idle_s", seconds(d.idleNs)},
                       {"utilisation_pct", d.utilisationPct},
                       {"energy_j", d.energyJ},
                       {"activity_energy_j", d.activityEnergyJ},
                       {"operations", d.operations},
                       {"errors", d.errors},
                       {"running_at_end", d.running}});
  }
  return out;
}

Json activitiesJson(const Trace& trace) {
  Json out = Json::array();
  for (uint32_t index : heldActivities(trace)) {
    const ActivityRecord& a = trace.activities[index];
    Json end = a.endNs < 0 ? Json(nullptr) : Json(seconds(a.endNs));
    out.push_back(Json{{"device", deviceName(trace, a.device)},
                       {"device_index", a.device},
                       {"label", labelName(trace, a.label)},
                       {"start_s", seconds(a.startNs)},
                       {"end_s", end},
                       {"duration_s", seconds(activityEndNs(trace, a) - a.startNs)},
                       {"energy_j", a.energyJ},
                       {"error", a.errorCode}});
  }
  return out;
}

Json collisionsJson(const Trace& trace) {
  Json out = Json::array();
  for (const CollisionRecord& c : trace.collisions)
    out.push_back(Json{{"time_s", seconds(c.timeNs)},
                       {"zone", labelName(trace, c.zone)},
                       {"device_a", deviceName(trace, c.deviceA)},
                       {"activity_a", labelName(trace, c.activityA)},
                       {"device_b", deviceName(trace, c.deviceB)},
                       {"activity_b", labelName(trace, c.activityB)}});
  return out;
}

Json faultsJson(const Trace& trace) {
  Json out = Json::array();
  for (const FaultRecord& f : trace.faults)
    out.push_back(Json{{"time_s", seconds(f.timeNs)}, {"source", f.source}, {"message", f.message}});
  return out;
}

// Wall-clock times as local "YYYY-MM-DD HH:MM:SS" (the plant's clock, as the plan is written).
std::string localTime(int64_t localNs) {
  const int64_t s = (localNs % kDayNs + kDayNs) % kDayNs / 1'000'000'000;
  char hms[16];
  std::snprintf(hms, sizeof hms, " %02d:%02d:%02d", static_cast<int>(s / 3600), static_cast<int>(s / 60 % 60), static_cast<int>(s % 60));
  return localDate(localNs) + hms;
}

Json productionJson(const ProductionReport& p) {
  Json shifts = Json::array(), days = Json::array(), stations = Json::array();
  for (const auto& s : p.shifts)
    shifts.push_back(Json{{"day", s.day},
                          {"shift", s.name},
                          {"start", localTime(s.startNs)},
                          {"end", localTime(s.endNs)},
                          {"watched_from", localTime(s.watchedFromNs)},
                          {"plan", s.plan},
                          {"plan_now", s.planNow},
                          {"actual", s.actual}});
  for (const auto& d : p.days) days.push_back(Json{{"day", d.day}, {"plan", d.plan}, {"plan_now", d.planNow}, {"actual", d.actual}});
  for (const auto& s : p.stations)
    stations.push_back(Json{{"device", s.name},
                            {"operation", s.operation.empty() ? Json(nullptr) : Json(s.operation)},
                            {"elapsed_s", seconds(s.elapsedNs)}});
  return Json{{"shifts", shifts}, {"days", days}, {"stations", stations}};
}

// "output activity" -> "output_activity", "IF" -> "if": the header as a JSON key.
std::string columnKey(const std::string& header) {
  std::string key;
  for (char c : header) key += c == ' ' ? '_' : asciiLower(c);
  return key;
}

// The rows of a table as objects keyed by its columns; rule rows get their firing counts.
Json tableJson(const TextTable& table, const std::vector<RuleFiring>* firings) {
  Json out = Json::array();
  for (size_t r = 0; r < table.rows.size(); ++r) {
    Json row = Json::object();
    for (size_t c = 0; c < table.header.size() && c < table.rows[r].size(); ++c) row[columnKey(table.header[c])] = table.rows[r][c];
    if (firings && r < firings->size()) {
      const RuleFiring& f = (*firings)[r];
      row["fired_scans"] = f.scans;
      row["first_fired_s"] = f.scans ? Json(seconds(f.firstNs)) : Json(nullptr);
      row["last_fired_s"] = f.scans ? Json(seconds(f.lastNs)) : Json(nullptr);
    }
    out.push_back(std::move(row));
  }
  return out;
}

Json diagramsJson(const std::vector<DiagramTablesSection>& diagrams) {
  Json out = Json::array();
  for (const DiagramTablesSection& d : diagrams)
    out.push_back(Json{{"program", d.program},
                       {"diagram", d.diagram},
                       {"lu_table", tableJson(d.lus, nullptr)},
                       {"rule_table", tableJson(d.rules, &d.firings)}});
  return out;
}

}  // namespace

std::string jsonReport(const Trace& trace, const Kpis& kpis, const std::vector<DiagramTablesSection>& diagrams,
                       const ProductionReport* production) {
  Json doc{{"schema", "virtcom.report"},
           {"schema_version", kJsonSchemaVersion},
           {"run", runJson(trace, kpis)},
           {"cycle", cycleJson(trace, kpis)},
           {"totals", Json{{"energy_j", kpis.totalEnergyJ},
                           {"operations", kpis.operations},
                           {"errors", kpis.errors},
                           {"collisions", kpis.collisions},
                           {"faults", kpis.faults}}},
           {"devices", devicesJson(trace, kpis)},
           {"activities", activitiesJson(trace)},
           {"collisions", collisionsJson(trace)},
           {"faults", faultsJson(trace)}};
  if (const ActivityLog& log = trace.activities; log.elidedCount() > 0)
    doc["activities_elided"] = Json{{"count", log.elidedCount()},
                                    {"from_s", seconds(log.elidedFromNs())},
                                    {"to_s", seconds(log.elidedToNs())}};
  if (!diagrams.empty()) doc["diagrams"] = diagramsJson(diagrams);
  if (production) doc["production"] = productionJson(*production);
  // `replace` turns invalid UTF-8 into U+FFFD instead of throwing: names come from user files.
  return doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace virtcom::report
