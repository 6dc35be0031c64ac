#include "hmi/stream_session.hpp"

#include <algorithm>
#include <bit>

#include <nlohmann/json.hpp>

#include "core/ascii.hpp"

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

// A tag's raw bus value as a JSON number or boolean.
Json signalValue(ElemType type, uint64_t raw) {
  if (type == ElemType::Bool) return raw != 0;
  if (isFloat(type)) return std::bit_cast<double>(raw);
  if (isInteger(type) && !isSignedInt(type)) return raw;
  return static_cast<int64_t>(raw);
}

Json activityJson(uint32_t index, const ActivityRecord& a) {
  return Json::array({index, a.device, a.label, a.startNs, a.endNs, a.errorCode, a.energyJ});
}

}  // namespace

StreamSession::StreamSession(const LiveState& live, const VariableCatalog& catalog, const std::vector<ElemType>& tagTypes,
                             const std::vector<std::string>& watch)
    : live_(live), catalog_(catalog), tagTypes_(tagTypes) {
  for (const std::string& name : watch) {
    auto ref = catalog_.find(name);
    if (ref) watched_.push_back({name, *ref, {}, false, false});
    else unknown_.push_back(name);
  }
}

std::string StreamSession::nextFrame() {
  Json frame;
  live_.read([&](const Snapshot& s) {
    if (s.seq == seq_ && !first_) return;
    seq_ = s.seq;
    frame = {{"t", s.nowNs}, {"paused", s.paused}, {"speed", s.speed}};
    if (first_ && !unknown_.empty()) frame["unknownWatch"] = unknown_;
    tags_.resize(s.tags.size());
    Json signals = Json::array();
    for (TagId id = 0; id < s.tags.size(); ++id)
      if (first_ || s.tags[id] != tags_[id]) {
        tags_[id] = s.tags[id];
        signals.push_back(Json::array({id, signalValue(tagTypes_[id], s.tags[id])}));
      }
    if (!signals.empty()) frame["signals"] = std::move(signals);
    Json activities = Json::array();
    for (size_t i = 0; i < open_.size();) {
      const ActivityRecord& a = s.activities[open_[i]];
      if (a.endNs < 0) {
        ++i;
        continue;
      }
      activities.push_back(activityJson(open_[i], a));
      open_[i] = open_.back();
      open_.pop_back();
    }
    for (; activities_ < s.activities.size(); ++activities_) {
      const ActivityRecord& a = s.activities[activities_];
      activities.push_back(activityJson(static_cast<uint32_t>(activities_), a));
      if (a.endNs < 0) open_.push_back(static_cast<uint32_t>(activities_));
    }
    if (!activities.empty()) frame["activities"] = std::move(activities);
    Json faults = Json::array();
    for (; faults_ < s.faults.size(); ++faults_)
      faults.push_back({{"t", s.faults[faults_].timeNs}, {"source", s.faults[faults_].source}, {"message", s.faults[faults_].message}});
    if (!faults.empty()) frame["faults"] = std::move(faults);
    Json collisions = Json::array();
    for (; collisions_ < s.collisions.size(); ++collisions_) {
      const CollisionRecord& c = s.collisions[collisions_];
      collisions.push_back({{"t", c.timeNs}, {"zone", c.zone}, {"a", c.deviceA}, {"b", c.deviceB}});
    }
    if (!collisions.empty()) frame["collisions"] = std::move(collisions);
    frame["kpi"] = {{"cycles", s.cyclesCompleted},
                    {"lastCycleNs", s.lastCycleNs},
                    {"cycleNs", s.nowNs - s.cycleStartNs},
                    {"energyJ", s.energyJ},
                    {"operations", s.activities.size()}};
    if (s.planned) frame["kpi"]["shift"] = {{"name", s.shift.shift}, {"planNow", s.shift.planNow}, {"parts", s.shift.parts}};
    if (first_ || s.forced != forced_) frame["forced"] = forced_ = s.forced;
    if (first_ || s.injected != injected_) frame["injected"] = injected_ = s.injected;
    Json vars = Json::array();
    for (Watched& w : watched_) {
      if (s.memory.empty()) break;
      std::string text = bc::formatValue(*catalog_.module(), w.ref, s.memory.data());
      bool forced = std::ranges::any_of(s.forced, [&](const std::string& f) { return iequalsAscii(f, w.name); });
      if (w.sent && text == w.last && forced == w.lastForced) continue;
      vars.push_back({{"name", w.name}, {"value", text}, {"forced", forced}});
      w.last = std::move(text);
      w.lastForced = forced;
      w.sent = true;
    }
    if (!vars.empty()) frame["vars"] = std::move(vars);
    if (s.ended && !ended_) {
      frame["ended"] = s.endMessage;
      ended_ = true;
    }
    first_ = false;
  });
  return frame.is_null() ? std::string() : frame.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace virtcom::hmi
