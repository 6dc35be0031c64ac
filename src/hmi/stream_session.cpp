#include "hmi/stream_session.hpp"

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/ascii.hpp"
#include "hmi/json_values.hpp"

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

}  // namespace

StreamSession::StreamSession(const LiveState& live, const VariableCatalog& catalog, const std::vector<ElemType>& tagTypes,
                             const std::vector<sfc::StepVariable>& steps, const std::vector<std::string>& watch)
    : live_(live), catalog_(catalog), tagTypes_(tagTypes), steps_(steps) {
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
    if (s.run != run_) {
      run_ = s.run;
      startOver();
      frame["reset"] = s.run;
    }
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
      // Running ones stay held (core/trace_logs.hpp); an ended one only while the window has it.
      const bool held = s.activities.held(open_[i]);
      if (held && s.activities[open_[i]].endNs < 0) {
        ++i;
        continue;
      }
      if (held) activities.push_back(activityJson(open_[i], s.activities[open_[i]]));
      open_[i] = open_.back();
      open_.pop_back();
    }
    for (; activities_ < s.activities.size(); ++activities_) {
      if (!s.activities.held(activities_)) continue;  // a viewer that fell a long run's window behind
      const ActivityRecord& a = s.activities[activities_];
      activities.push_back(activityJson(static_cast<uint32_t>(activities_), a));
      if (a.endNs < 0) open_.push_back(static_cast<uint32_t>(activities_));
    }
    if (!activities.empty()) frame["activities"] = std::move(activities);
    if (Json stations = changedStations(s); !stations.empty()) frame["stations"] = std::move(stations);
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
    if (!steps_.empty() && !s.memory.empty()) {
      Json active = activeSteps(s);
      if (first_ || active != stepsSent_) frame["steps"] = stepsSent_ = std::move(active);
    }
    if (Json rules = changedRules(s); !rules.empty()) frame["rules"] = std::move(rules);
    if (Json belts = changedBelts(s); !belts.empty()) frame["belts"] = std::move(belts);
    if (s.ended && !ended_) {
      frame["ended"] = s.endMessage;
      ended_ = true;
    }
    first_ = false;
  });
  return frame.is_null() ? std::string() : frame.dump(-1, ' ', false, Json::error_handler_t::replace);
}

void StreamSession::startOver() {
  first_ = true;
  activities_ = faults_ = collisions_ = 0;
  open_.clear();
  ended_ = false;
  rules_.clear();
  belts_.clear();
  stations_.clear();
  for (Watched& w : watched_) w.sent = false;
}

// [step index, milliseconds in the step] of every active step (the X flags and T times in the
// published memory image: the panel costs the scan nothing).
Json StreamSession::activeSteps(const Snapshot& s) const {
  Json active = Json::array();
  for (size_t i = 0; i < steps_.size(); ++i) {
    if (s.memory[steps_[i].activeAddress] == 0) continue;
    int32_t ms = 0;
    std::memcpy(&ms, s.memory.data() + steps_[i].timeAddress, sizeof ms);
    active.push_back(Json::array({i, ms}));
  }
  return active;
}

// [rule index, fire count, last fired ns] of the rules that fired since the last frame.
Json StreamSession::changedRules(const Snapshot& s) {
  Json changed = Json::array();
  rules_.resize(s.rules.size());
  for (size_t i = 0; i < s.rules.size(); ++i) {
    if (!first_ && s.rules[i].scans == rules_[i].scans) continue;
    rules_[i] = s.rules[i];
    changed.push_back(Json::array({i, s.rules[i].scans, s.rules[i].lastNs}));
  }
  return changed;
}

// [trace device, operation label or -1 when idle, since ns] of the stations that changed.
Json StreamSession::changedStations(const Snapshot& s) {
  Json changed = Json::array();
  stations_.resize(s.stations.size());
  for (size_t d = 0; d < s.stations.size(); ++d) {
    if (!first_ && s.stations[d] == stations_[d]) continue;
    stations_[d] = s.stations[d];
    changed.push_back(Json::array({d, s.stations[d].label, s.stations[d].sinceNs}));
  }
  return changed;
}

// {device, parts: [[position mm, kind], ...]} of the belts whose parts moved.
Json StreamSession::changedBelts(const Snapshot& s) {
  Json changed = Json::array();
  belts_.resize(s.belts.size());
  for (size_t b = 0; b < s.belts.size(); ++b) {
    const BeltParts& now = s.belts[b];
    if (!first_ && now.positionMm == belts_[b].positionMm && now.kind == belts_[b].kind) continue;
    belts_[b] = now;
    Json parts = Json::array();
    for (size_t i = 0; i < now.positionMm.size(); ++i) parts.push_back(Json::array({now.positionMm[i], now.kind[i]}));
    changed.push_back({{"device", now.device}, {"parts", std::move(parts)}});
  }
  return changed;
}

}  // namespace virtcom::hmi
