#include "plant/conveyor.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "plant/config_helpers.hpp"
#include "plant/motion_profile.hpp"

namespace virtcom::plant {
namespace {
int64_t metresToNm(double m) { return static_cast<int64_t>(std::llround(m * 1e9)); }
}  // namespace

Conveyor::Conveyor(std::string name, Params params) : Device(std::move(name), "conveyor"), p_(std::move(params)) {
  runPort_ = addPort("run", ElemType::Bool, PortDir::In, "belt runs while true");
  reversePort_ = addPort("reverse", ElemType::Bool, PortDir::In, "run towards position 0");
  movingPort_ = addPort("moving", ElemType::Bool, PortDir::Out, "belt is moving");
  for (auto& s : p_.sensors) s.port = addPort(s.name, ElemType::Bool, PortDir::Out, "part present at the sensor");
  for (auto& pusher : p_.pushers)
    pusher.port = addPort(pusher.name, ElemType::Bool, PortDir::In, "push the part at the pusher into its bin while true");
  const size_t bins = p_.pushers.size() + (p_.discharge ? 1 : 0);
  firstCountPort_ = ports().size();
  auto kindName = [&](size_t k) { return p_.kinds.empty() ? std::string("parts") : p_.kinds[k]; };
  for (size_t b = 0; b < bins; ++b)
    for (size_t k = 0; k < kindCount(); ++k)
      addPort((b < p_.pushers.size() ? p_.pushers[b].name : std::string("end")) + "_" + kindName(k), ElemType::Dint,
              PortDir::Out, "parts of this kind in the bin");
  hasProducedPorts_ = !p_.kinds.empty();
  firstProducedPort_ = ports().size();
  if (hasProducedPorts_)
    for (size_t k = 0; k < kindCount(); ++k)
      addPort("produced_" + kindName(k), ElemType::Dint, PortDir::Out, "parts of this kind put on the belt");
  binCounts_.assign(bins * kindCount(), 0);
  produced_.assign(kindCount(), 0);
  // A non-positive length (a mistake the factory reported) must not size the buffer.
  const size_t capacity =
      p_.partLengthNm > 0 && p_.lengthNm > 0 ? static_cast<size_t>(p_.lengthNm / p_.partLengthNm) + 1 : 1;
  parts_.reserve(std::max(capacity, p_.initialPartsNm.size()));
  parts_ = p_.initialPartsNm;
  std::sort(parts_.begin(), parts_.end());
  partKinds_.reserve(parts_.capacity());
  partKinds_.assign(parts_.size(), 0);  // parts present at the start are of the first kind
  spawnTimerNs_ = p_.spawnIntervalNs;  // first part at the first running tick
}

void Conveyor::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  runLabel_ = trace.internLabel("Running");
}

bool Conveyor::atEnd() const { return !parts_.empty() && parts_.back() + p_.partLengthNm >= p_.lengthNm; }

// Takes part `part` off the belt into bin `bin`. Within the reserved vectors: no allocation.
void Conveyor::drop(size_t part, size_t bin) {
  ++binCounts_[bin * kindCount() + partKinds_[part]];
  parts_.erase(parts_.begin() + static_cast<std::ptrdiff_t>(part));
  partKinds_.erase(partKinds_.begin() + static_cast<std::ptrdiff_t>(part));
}

void Conveyor::move(int64_t dsNm) {
  if (!reverse_) {
    // with discharge there is no end stopper: parts run off the end into the end bin
    int64_t limit = p_.discharge ? INT64_MAX / 2 : p_.lengthNm - p_.partLengthNm;
    for (size_t i = parts_.size(); i-- > 0;) {
      parts_[i] = std::min(parts_[i] + dsNm, limit);
      limit = parts_[i] - p_.partLengthNm;
    }
    while (p_.discharge && !parts_.empty() && parts_.back() >= p_.lengthNm) drop(parts_.size() - 1, p_.pushers.size());
  } else {
    int64_t limit = 0;
    for (int64_t& part : parts_) {
      part = std::max(part - dsNm, limit);
      limit = part + p_.partLengthNm;
    }
  }
}

void Conveyor::spawn(int64_t dtNs) {
  if (p_.spawnIntervalNs <= 0 || reverse_) return;
  spawnTimerNs_ += dtNs;
  const bool startFree = parts_.empty() || parts_.front() >= p_.partLengthNm;
  if (spawnTimerNs_ >= p_.spawnIntervalNs && startFree && lotLeft() && parts_.size() < parts_.capacity()) {
    const uint8_t kind = p_.pattern.empty() ? 0 : p_.pattern[spawned_ % p_.pattern.size()];
    parts_.insert(parts_.begin(), 0);  // within the reserved capacity: no allocation
    partKinds_.insert(partKinds_.begin(), kind);
    ++produced_[kind];
    ++spawned_;
    spawnTimerNs_ = 0;
  }
}

// Motion over dtNs, split at the spawn times that fall inside it.
void Conveyor::advance(int64_t dtNs) {
  while (dtNs > 0) {
    int64_t chunk = dtNs;
    if (p_.spawnIntervalNs > 0 && !reverse_) {
      const int64_t due = p_.spawnIntervalNs - spawnTimerNs_;
      if (due > 0 && due < chunk) chunk = due;
    }
    move(std::llround(p_.speed * static_cast<double>(chunk)));  // m/s x ns = nm
    spawn(chunk);
    dtNs -= chunk;
  }
}

// Motion over dtNs as the base ticks in it would have moved the belt one by one: after ticks
// skipped by event-driven time the positions are the same integers, roundings included.
void Conveyor::advanceTicks(int64_t dtNs, int64_t tickNs) {
  if (tickNs <= 0) tickNs = dtNs;
  while (dtNs > 0) {
    const int64_t chunk = std::min(dtNs, tickNs);
    advance(chunk);
    dtNs -= chunk;
  }
}

void Conveyor::step(const StepContext& ctx) {
  const int64_t dtNs = started_ ? ctx.nowNs - lastNs_ : 0;
  started_ = true;
  lastNs_ = ctx.nowNs;
  tickNs_ = ctx.dtNs;
  // A part taken from the end (its fact cleared by another device) leaves the belt.
  if (p_.endFact >= 0 && endPublished_ && !ctx.world.hasFact(static_cast<uint32_t>(p_.endFact)) && atEnd()) {
    parts_.pop_back();
    partKinds_.pop_back();
  }
  // Motion since the previous tick, under the inputs of the previous tick.
  if (moving_) advanceTicks(dtNs, ctx.dtNs);
  const bool run = ctx.bus.getBool(tag(runPort_));
  reverse_ = ctx.bus.getBool(tag(reversePort_));
  if (run && !moving_) {
    runStartNs_ = ctx.nowNs;
    activity_ = ctx.trace.beginActivity(traceIndex(), runLabel_, ctx.nowNs);
    spawn(0);
  } else if (!run && moving_) {
    busyNs_ += ctx.nowNs - runStartNs_;
    ctx.trace.endActivity(activity_, ctx.nowNs, p_.powerW * static_cast<double>(ctx.nowNs - runStartNs_) * 1e-9);
  }
  moving_ = run;
  ctx.bus.setBool(tag(movingPort_), moving_);
  push(ctx.bus);
  for (const auto& s : p_.sensors) {
    bool covered = false;
    for (size_t i = 0; i < parts_.size(); ++i)
      if (covers(parts_[i], s.positionNm) && (s.kindMask == 0 || (s.kindMask >> partKinds_[i]) & 1)) covered = true;
    ctx.bus.setBool(tag(s.port), covered);
  }
  publishCounts(ctx.bus);
  if (p_.endFact >= 0) {
    endPublished_ = atEnd();
    ctx.world.setFact(static_cast<uint32_t>(p_.endFact), endPublished_);
  }
}

// Every pusher whose command is on pushes the parts covering its position into its bin.
void Conveyor::push(const TagBus& bus) {
  pushing_ = false;
  for (size_t b = 0; b < p_.pushers.size(); ++b) {
    if (!bus.getBool(tag(p_.pushers[b].port))) continue;
    pushing_ = true;
    for (size_t i = parts_.size(); i-- > 0;)
      if (covers(parts_[i], p_.pushers[b].positionNm)) drop(i, b);
  }
}

void Conveyor::publishCounts(TagBus& bus) const {
  for (size_t i = 0; i < binCounts_.size(); ++i) bus.setInt(tag(firstCountPort_ + i), binCounts_[i]);
  if (hasProducedPorts_)
    for (size_t k = 0; k < produced_.size(); ++k) bus.setInt(tag(firstProducedPort_ + k), produced_[k]);
}

// The first tick at which a part can reach a sensor edge, the end, the part ahead, or free the
// start for a waiting spawn; the next spawn. A tick moves a part by at most round(speed x tick)
// + 1 nm (a tick split at a spawn rounds twice), so the count of ticks is a lower bound.
int64_t Conveyor::nextEventNs() const {
  if (!started_) return 0;
  if (!moving_ || p_.speed <= 0) return INT64_MAX;
  if (pushing_) return 0;
  int64_t best = INT64_MAX;  // nm still to travel until something visible changes
  auto consider = [&](int64_t d) {
    if (d > 0 && d < best) best = d;
  };
  const int64_t len = p_.partLengthNm;
  for (size_t i = 0; i < parts_.size(); ++i) {
    const int64_t p = parts_[i];
    for (const auto& s : p_.sensors) {
      const int64_t x = s.positionNm;
      if (!reverse_) {
        consider(x - (p + len));  // front edge reaches the sensor
        consider(x - p + 1);      // rear edge leaves it
      } else {
        consider(p - x);
        consider(p + len - x + 1);
      }
    }
    const int64_t endNm = p_.discharge ? p_.lengthNm : p_.lengthNm - len;  // falls off, or stops
    if (!reverse_) consider((i + 1 < parts_.size() ? parts_[i + 1] - len : endNm) - p);
    else consider(p - (i > 0 ? parts_[i - 1] + len : 0));
  }
  const bool spawning = p_.spawnIntervalNs > 0 && !reverse_ && lotLeft();
  if (spawning && !parts_.empty()) consider(len - parts_.front());  // a spawn waits for a free start
  int64_t next = INT64_MAX;
  if (best != INT64_MAX) {
    const int64_t maxStepNm = std::llround(p_.speed * static_cast<double>(tickNs_)) + 1;
    next = lastNs_ + (best + maxStepNm - 1) / maxStepNm * tickNs_;
  }
  if (spawning) next = std::min(next, lastNs_ + std::max<int64_t>(p_.spawnIntervalNs - spawnTimerNs_, 1));
  return next;
}

void Conveyor::finish(int64_t endNs, Trace& trace) {
  DeviceTotals& t = trace.totals[traceIndex()];
  t.busyNs = busyNs_ + (moving_ ? endNs - runStartNs_ : 0);
  t.energyJ = p_.idlePowerW * static_cast<double>(endNs) * 1e-9 + p_.powerW * static_cast<double>(t.busyNs) * 1e-9;
}

namespace {

// `part_kinds: [steel, bad_steel, plastic]`: the kinds, in order of first appearance, and the
// repeating order of the spawned parts.
void readPartKinds(ConfigReader& cfg, Conveyor::Params& p) {
  const ConfigNode* list = cfg.child("part_kinds");
  if (!list) return;
  if (list->kind() != ConfigNode::Kind::List || list->items().empty()) {
    cfg.error(list->loc(), "'part_kinds' must be a list of kind names such as [steel, plastic, bad_steel]");
    return;
  }
  for (const auto& item : list->items()) {
    if (item.kind() != ConfigNode::Kind::Scalar || item.scalar().empty()) {
      cfg.error(item.loc(), "'part_kinds': expected a kind name");
      continue;
    }
    auto known = std::find(p.kinds.begin(), p.kinds.end(), item.scalar());
    if (known == p.kinds.end()) {
      if (p.kinds.size() == Conveyor::kMaxKinds) {
        cfg.error(item.loc(), "'part_kinds': at most 32 different kinds");
        continue;
      }
      known = p.kinds.insert(p.kinds.end(), item.scalar());
    }
    p.pattern.push_back(static_cast<uint8_t>(known - p.kinds.begin()));
  }
}

// A sensor's `detects: [kind, ...]` as a bit mask over the belt's kinds; absent: 0 (any part).
uint32_t kindMask(ConfigReader& cfg, const std::vector<std::string>& kinds) {
  const ConfigNode* list = cfg.child("detects");
  if (!list) return 0;
  std::vector<const ConfigNode*> names;
  if (list->kind() == ConfigNode::Kind::Scalar) names.push_back(list);
  else if (list->kind() == ConfigNode::Kind::List)
    for (const auto& item : list->items()) names.push_back(&item);
  uint32_t mask = 0;
  for (const ConfigNode* n : names) {
    auto k = std::find(kinds.begin(), kinds.end(), n->scalar());
    if (n->kind() != ConfigNode::Kind::Scalar || k == kinds.end()) {
      cfg.error(n->loc(), "'detects': '" + n->scalar() + "' is not one of the conveyor's part_kinds (" +
                              (kinds.empty() ? std::string("none declared") : joinNames(kinds)) + ")");
      continue;
    }
    mask |= 1u << (k - kinds.begin());
  }
  if (names.empty()) cfg.error(list->loc(), "'detects' must list part kinds such as [bad_steel, bad_plastic]");
  return mask;
}

// Sensor and pusher names become port names: they must not clash with each other or the belt's.
void checkPortName(ConfigReader& cfg, std::vector<std::string>& names, const char* what, const std::string& name,
                   SourceLocation loc) {
  if (std::find(names.begin(), names.end(), name) != names.end())
    cfg.error(loc, std::string(what) + " name '" + name + "' clashes with a conveyor port (" + joinNames(names) + ")");
  names.push_back(name);
}

}  // namespace

bool Conveyor::changesParameter(std::string_view key) const {
  return key == "speed" || key == "spawn_interval" || key == "spawn_count";
}

void Conveyor::swapParameters(Device& edited) {
  Params& other = static_cast<Conveyor&>(edited).p_;
  std::swap(p_.speed, other.speed);
  std::swap(p_.spawnIntervalNs, other.spawnIntervalNs);
  std::swap(p_.spawnCount, other.spawnCount);
}

std::unique_ptr<Device> makeConveyor(const std::string& name, ConfigReader& cfg, World& world) {
  Conveyor::Params p;
  p.speed = cfg.requireQuantity("speed", Dimension::Speed);
  const double length = cfg.requireQuantity("length", Dimension::Length);
  const double partLength = cfg.optQuantity("part_length", Dimension::Length, 0.1);
  p.lengthNm = metresToNm(length);
  p.partLengthNm = metresToNm(partLength);
  p.spawnIntervalNs = optDurationNs(cfg, "spawn_interval", 0);
  p.idlePowerW = cfg.optQuantity("idle_power", Dimension::Power, 0);
  p.powerW = cfg.optQuantity("power", Dimension::Power, 0);
  const std::string endFact = cfg.optString("end_fact", "");
  if (!endFact.empty()) p.endFact = static_cast<int32_t>(world.fact(endFact));
  for (const char* key : {"speed", "length", "part_length"})
    if (cfg.has(key) && cfg.node().find(key)->kind() == ConfigNode::Kind::Scalar) {
      double v = key[0] == 's' ? p.speed : key[0] == 'l' ? length : partLength;
      if (!(v > 0)) cfg.error(cfg.node().find(key)->loc(), std::string("'") + key + "' must be greater than 0");
    }
  if (p.partLengthNm > p.lengthNm) cfg.error(cfg.node().loc(), "'part_length' must not exceed the conveyor 'length'");
  if (const ConfigNode* parts = cfg.child("initial_parts")) {
    if (parts->kind() != ConfigNode::Kind::List) {
      cfg.error(parts->loc(), "'initial_parts' must be a list of positions such as [0 mm, 300 mm]");
    } else {
      for (const auto& item : parts->items()) {
        double v = 0;
        std::string problem = item.kind() == ConfigNode::Kind::Scalar ? parseQuantity(item.scalar(), Dimension::Length, v)
                                                                       : "expected a position";
        if (!problem.empty()) cfg.error(item.loc(), "'initial_parts': " + problem);
        else if (metresToNm(v) < 0 || metresToNm(v) + p.partLengthNm > p.lengthNm)
          cfg.error(item.loc(), "'initial_parts': part does not fit on the belt");
        p.initialPartsNm.push_back(metresToNm(v));
      }
      std::vector<int64_t> sorted = p.initialPartsNm;
      std::sort(sorted.begin(), sorted.end());
      for (size_t i = 1; i < sorted.size(); ++i)
        if (sorted[i] < sorted[i - 1] + p.partLengthNm) cfg.error(parts->loc(), "'initial_parts': parts overlap");
    }
  }
  readPartKinds(cfg, p);
  p.spawnCount = cfg.optInt("spawn_count", 0);
  if (p.spawnCount < 0) cfg.error(cfg.node().find("spawn_count")->loc(), "'spawn_count' must not be negative");
  p.discharge = cfg.optBool("discharge", false);
  std::vector<std::string> portNames = {"run", "reverse", "moving"};
  if (const ConfigNode* sensors = mapChild(cfg, "sensors", false)) {
    ConfigReader sr(*sensors, cfg.diags(), "sensors of conveyor '" + name + "'");
    for (const auto& [sensorName, node] : sensors->entries()) {
      Conveyor::SensorSpec s;
      s.name = sensorName;
      if (node.kind() == ConfigNode::Kind::Map) {  // {at: 800 mm, detects: [bad_steel]}
        ConfigReader one(node, cfg.diags(), "sensor '" + sensorName + "' of conveyor '" + name + "'");
        s.positionNm = metresToNm(one.requireQuantity("at", Dimension::Length));
        s.kindMask = kindMask(one, p.kinds);
        one.rejectUnknownKeys();
      } else {
        s.positionNm = metresToNm(sr.requireQuantity(sensorName, Dimension::Length));
      }
      checkPortName(sr, portNames, "sensor", sensorName, sensors->keyLoc(sensorName));
      p.sensors.push_back(std::move(s));
    }
  }
  if (const ConfigNode* pushers = mapChild(cfg, "pushers", false)) {
    ConfigReader pr(*pushers, cfg.diags(), "pushers of conveyor '" + name + "'");
    for (const auto& [pusherName, node] : pushers->entries()) {
      (void)node;
      const int64_t at = metresToNm(pr.requireQuantity(pusherName, Dimension::Length));
      if (at < 0 || at > p.lengthNm) pr.error(node.loc(), "pusher '" + pusherName + "' is not on the belt");
      checkPortName(pr, portNames, "pusher", pusherName, pushers->keyLoc(pusherName));
      p.pushers.push_back({pusherName, at, 0});
    }
  }
  return std::make_unique<Conveyor>(name, std::move(p));
}

}  // namespace virtcom::plant
