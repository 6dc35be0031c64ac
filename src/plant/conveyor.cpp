#include "plant/conveyor.hpp"

#include <algorithm>
#include <cmath>

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
  // A non-positive length (a mistake the factory reported) must not size the buffer.
  const size_t capacity =
      p_.partLengthNm > 0 && p_.lengthNm > 0 ? static_cast<size_t>(p_.lengthNm / p_.partLengthNm) + 1 : 1;
  parts_.reserve(std::max(capacity, p_.initialPartsNm.size()));
  parts_ = p_.initialPartsNm;
  std::sort(parts_.begin(), parts_.end());
  spawnTimerNs_ = p_.spawnIntervalNs;  // first part at the first running tick
}

void Conveyor::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  runLabel_ = trace.internLabel("Running");
}

bool Conveyor::atEnd() const { return !parts_.empty() && parts_.back() + p_.partLengthNm >= p_.lengthNm; }

void Conveyor::move(int64_t dsNm) {
  if (!reverse_) {
    int64_t limit = p_.lengthNm - p_.partLengthNm;
    for (size_t i = parts_.size(); i-- > 0;) {
      parts_[i] = std::min(parts_[i] + dsNm, limit);
      limit = parts_[i] - p_.partLengthNm;
    }
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
  if (spawnTimerNs_ >= p_.spawnIntervalNs && startFree && parts_.size() < parts_.capacity()) {
    parts_.insert(parts_.begin(), 0);  // within the reserved capacity: no allocation
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

void Conveyor::step(const StepContext& ctx) {
  const int64_t dtNs = started_ ? ctx.nowNs - lastNs_ : 0;
  started_ = true;
  lastNs_ = ctx.nowNs;
  // A part taken from the end (its fact cleared by another device) leaves the belt.
  if (p_.endFact >= 0 && endPublished_ && !ctx.world.hasFact(static_cast<uint32_t>(p_.endFact)) && atEnd())
    parts_.pop_back();
  // Motion since the previous tick, under the inputs of the previous tick.
  if (moving_) advance(dtNs);
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
  for (const auto& s : p_.sensors) {
    bool covered = false;
    for (int64_t part : parts_)
      if (part <= s.positionNm && s.positionNm <= part + p_.partLengthNm) covered = true;
    ctx.bus.setBool(tag(s.port), covered);
  }
  if (p_.endFact >= 0) {
    endPublished_ = atEnd();
    ctx.world.setFact(static_cast<uint32_t>(p_.endFact), endPublished_);
  }
}

int64_t Conveyor::nextEventNs() const {
  if (!moving_ || p_.speed <= 0) return INT64_MAX;
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
    if (!reverse_) consider((i + 1 < parts_.size() ? parts_[i + 1] - len : p_.lengthNm - len) - p);
    else consider(p - (i > 0 ? parts_[i - 1] + len : 0));
  }
  int64_t next = INT64_MAX;
  if (best != INT64_MAX) next = lastNs_ + static_cast<int64_t>(std::ceil(static_cast<double>(best) / p_.speed));
  if (p_.spawnIntervalNs > 0 && !reverse_) next = std::min(next, lastNs_ + std::max<int64_t>(p_.spawnIntervalNs - spawnTimerNs_, 1));
  return next;
}

void Conveyor::finish(int64_t endNs, Trace& trace) {
  DeviceTotals& t = trace.totals[traceIndex()];
  t.busyNs = busyNs_ + (moving_ ? endNs - runStartNs_ : 0);
  t.energyJ = p_.idlePowerW * static_cast<double>(endNs) * 1e-9 + p_.powerW * static_cast<double>(t.busyNs) * 1e-9;
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
  if (const ConfigNode* sensors = mapChild(cfg, "sensors", false)) {
    ConfigReader sr(*sensors, cfg.diags(), "sensors of conveyor '" + name + "'");
    for (const auto& [sensorName, node] : sensors->entries()) {
      (void)node;
      Conveyor::SensorSpec s;
      s.name = sensorName;
      s.positionNm = metresToNm(sr.requireQuantity(sensorName, Dimension::Length));
      if (sensorName == "run" || sensorName == "reverse" || sensorName == "moving")
        sr.error(sensors->keyLoc(sensorName), "sensor name '" + sensorName + "' clashes with a conveyor port");
      p.sensors.push_back(std::move(s));
    }
  }
  return std::make_unique<Conveyor>(name, std::move(p));
}

}  // namespace virtcom::plant
