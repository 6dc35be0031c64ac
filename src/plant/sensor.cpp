#include "plant/sensor.hpp"

#include <utility>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Sensor::Sensor(std::string name, uint32_t fact, int64_t delayNs, bool invert)
    : Device(std::move(name), "sensor"), fact_(fact), delayNs_(delayNs), invert_(invert) {
  valuePort_ = addPort("value", ElemType::Bool, PortDir::Out, "the sensed fact (after delay / inversion)");
}

void Sensor::step(const StepContext& ctx) {
  const bool raw = ctx.world.hasFact(fact_) != invert_;
  if (!started_) {  // the initial state is known without delay
    started_ = true;
    value_ = raw;
  } else if (raw == value_) {
    pending_ = false;
  } else {
    if (!pending_) {
      pending_ = true;
      pendingSinceNs_ = ctx.nowNs;
    }
    if (ctx.nowNs - pendingSinceNs_ >= delayNs_) {
      value_ = raw;
      pending_ = false;
    }
  }
  const bool out = faults_.stuckOutput < 0 ? value_ : faults_.stuckOutput != 0;
  ctx.bus.setBool(tag(valuePort_), out);
}

void Sensor::swapParameters(Device& edited) {
  auto& other = static_cast<Sensor&>(edited);
  std::swap(delayNs_, other.delayNs_);
  std::swap(invert_, other.invert_);
}

int64_t Sensor::nextEventNs() const { return pending_ ? pendingSinceNs_ + delayNs_ : INT64_MAX; }

std::unique_ptr<Device> makeSensor(const std::string& name, ConfigReader& cfg, World& world) {
  const std::string fact = cfg.requireString("fact");
  const int64_t delayNs = optDurationNs(cfg, "delay", 0);
  const bool invert = cfg.optBool("invert", false);
  if (cfg.has("fact") && fact.empty()) cfg.error(cfg.node().find("fact")->loc(), "'fact' needs a fact name");
  return std::make_unique<Sensor>(name, world.fact(fact), delayNs, invert);
}

}  // namespace virtcom::plant
