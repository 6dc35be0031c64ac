#include "report/json_report.hpp"

#include <nlohmann/json.hpp>

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
  if (t.ticks > 0)
    run["time"] = Json{{"mode", t.eventDriven ? "event" : "tick"},
                       {"ticks", t.ticks},
                       {"ticks_skipped", t.ticksSkipped},
                       {"jumps", t.jumps}};
  return run;
}

Json cycleJson(const Kpis& k) {
  return Json{{"measured", k.cycleMeasured},
              {"start_s", seconds(k.windowStartNs)},
              {"end_s", seconds(k.windowEndNs)},
              {"time_s", seconds(k.cycleTimeNs)}};
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
  for (const ActivityRecord& a : trace.activities) {
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

}  // namespace

std::string jsonReport(const Trace& trace, const Kpis& kpis) {
  Json doc{{"schema", "virtcom.report"},
           {"schema_version", kJsonSchemaVersion},
           {"run", runJson(trace, kpis)},
           {"cycle", cycleJson(kpis)},
           {"totals", Json{{"energy_j", kpis.totalEnergyJ},
                           {"operations", kpis.operations},
                           {"errors", kpis.errors},
                           {"collisions", kpis.collisions},
                           {"faults", kpis.faults}}},
           {"devices", devicesJson(trace, kpis)},
           {"activities", activitiesJson(trace)},
           {"collisions", collisionsJson(trace)},
           {"faults", faultsJson(trace)}};
  // `replace` turns invalid UTF-8 into U+FFFD instead of throwing: names come from user files.
  return doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace virtcom::report
