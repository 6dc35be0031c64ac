#include "hmi/history_api.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "hmi/json_values.hpp"

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

Response ok(const Json& body) {
  Response r;
  r.body = body.dump(-1, ' ', false, Json::error_handler_t::replace);
  return r;
}

Json runJson(const history::RunSummary& r) {
  return {{"id", r.id},         {"cell", r.cellName},         {"wallStartNs", r.wallStartNs}, {"endNs", r.endNs},
          {"ended", r.ended},   {"endReason", r.endReason},   {"changes", r.changes},         {"activities", r.activities},
          {"drops", r.drops},   {"writerError", r.writerError}};
}

Json devicesJson(const std::vector<DeviceInfo>& devices) {
  Json list = Json::array();
  for (const DeviceInfo& d : devices) list.push_back({{"name", d.name}, {"type", d.type}, {"group", d.group}});
  return list;
}

Json activitiesJson(const std::vector<ActivityRecord>& activities) {
  Json list = Json::array();
  for (size_t i = 0; i < activities.size(); ++i) list.push_back(activityJson(static_cast<uint32_t>(i), activities[i]));
  return list;
}

Response noRun(int64_t run) { return errorResponse(404, "no run " + std::to_string(run) + " in the history (GET /api/history/runs lists them)"); }

}  // namespace

std::expected<std::unique_ptr<HistoryApi>, std::string> HistoryApi::open(const std::string& path) {
  auto reader = history::HistoryReader::open(path);
  if (!reader) return std::unexpected(reader.error());
  return std::make_unique<HistoryApi>(std::move(*reader));
}

Response HistoryApi::handle(const ParsedRequest& r) {
  std::lock_guard lock(mutex_);
  switch (r.route) {
    case Route::HistoryRuns: return runs();
    case Route::HistoryRange: return range(r);
    case Route::HistoryState: return state(r);
    default: return errorResponse(500, "not a history route");
  }
}

Response HistoryApi::runs() {
  Json list = Json::array();
  for (const history::RunSummary& r : reader_.runs()) list.push_back(runJson(r));
  return ok(Json{{"runs", std::move(list)}});
}

Response HistoryApi::range(const ParsedRequest& r) {
  auto run = reader_.run(r.run);
  if (!run) return noRun(r.run);
  const std::vector<SignalInfo> signals = reader_.signals(r.run);
  std::vector<TagId> wanted;
  for (const std::string& name : r.signals) {
    auto it = std::ranges::find(signals, name, &SignalInfo::name);
    if (it == signals.end()) return errorResponse(400, "run " + std::to_string(r.run) + " did not record a signal '" + name + "'");
    wanted.push_back(static_cast<TagId>(it - signals.begin()));
  }
  const history::TimeRange range{r.fromNs, r.toNs};
  Json series = Json::array();
  for (const history::Series& s : reader_.series(r.run, wanted, range, static_cast<size_t>(r.points))) {
    const SignalInfo& info = signals[s.signal];
    Json points = Json::array();
    for (const SignalChange& c : s.points) points.push_back(Json::array({c.timeNs, signalValue(info.type, c.raw)}));
    series.push_back({{"name", info.name},
                      {"before", signalValue(info.type, s.before)},
                      {"points", std::move(points)},
                      {"changes", s.changes},
                      {"decimated", s.decimated()}});
  }
  Json names = Json::array();
  for (const SignalInfo& info : signals) names.push_back(info.name);
  return ok(Json{{"run", runJson(*run)},
                 {"signals", std::move(names)},
                 {"from", r.fromNs},
                 {"to", std::min(r.toNs, run->endNs)},
                 {"devices", devicesJson(reader_.devices(r.run))},
                 {"labels", reader_.labels(r.run)},
                 {"activities", activitiesJson(reader_.activities(r.run, range))},
                 {"series", std::move(series)}});
}

Response HistoryApi::state(const ParsedRequest& r) {
  auto run = reader_.run(r.run);
  if (!run) return noRun(r.run);
  const int64_t at = r.fromNs;
  const std::vector<SignalInfo> signals = reader_.signals(r.run);
  // The values at `at`: those just before at + 1 ns (a change at `at` counts).
  const std::vector<uint64_t> values = reader_.valuesBefore(r.run, at == INT64_MAX ? at : at + 1);
  Json byName = Json::object();
  for (size_t i = 0; i < signals.size() && i < values.size(); ++i) byName[signals[i].name] = signalValue(signals[i].type, values[i]);
  std::vector<ActivityRecord> running = reader_.activities(r.run, {at, at});
  std::erase_if(running, [at](const ActivityRecord& a) { return a.endNs >= 0 && a.endNs <= at; });
  return ok(Json{{"run", runJson(*run)},
                 {"at", at},
                 {"values", std::move(byName)},
                 {"devices", devicesJson(reader_.devices(r.run))},
                 {"labels", reader_.labels(r.run)},
                 {"activities", activitiesJson(running)}});
}

}  // namespace virtcom::hmi
