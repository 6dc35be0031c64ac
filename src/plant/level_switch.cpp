#include "plant/level_switch.hpp"

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

LevelSwitch::LevelSwitch(std::string name, uint32_t vessel, Params params)
    : Device(std::move(name), "level_switch"), vessel_(vessel), p_(params) {
  valuePort_ = addPort("value", ElemType::Bool, PortDir::Out, "the level is beyond the threshold (with hysteresis)");
}

void LevelSwitch::step(const StepContext& ctx) {
  const Vessel& v = ctx.world.vesselAt(vessel_);
  const double level = p_.inPercent ? v.levelRatio() : v.levelM();
  if (p_.above) value_ = value_ ? level >= p_.threshold - p_.hysteresis : level >= p_.threshold;
  else value_ = value_ ? level <= p_.threshold + p_.hysteresis : level <= p_.threshold;
  ctx.bus.setBool(tag(valuePort_), faults_.stuckOutput < 0 ? value_ : faults_.stuckOutput != 0);
}

namespace {

// A level: `95 %` (of the capacity) or a height such as `900 mm`; sets `inPercent` to the kind.
double readLevel(ConfigReader& cfg, const std::string& key, bool& inPercent) {
  const ConfigNode* n = cfg.child(key);
  if (!n || n->kind() != ConfigNode::Kind::Scalar) {
    if (n) cfg.error(n->loc(), "'" + key + "' must be a level such as 95 % or 900 mm");
    return 0;
  }
  double v = 0;
  if (parseQuantity(n->scalar(), Dimension::Ratio, v).empty()) {
    inPercent = true;
  } else if (parseQuantity(n->scalar(), Dimension::Length, v).empty()) {
    inPercent = false;
  } else {
    cfg.error(n->loc(), "'" + key + "': expected a level in % of the capacity (e.g. 95 %) or a height (e.g. 900 mm), found '" +
                            n->scalar() + "'");
  }
  if (v < 0) cfg.error(n->loc(), "'" + key + "' must not be negative");
  return v;
}

}  // namespace

std::unique_ptr<Device> makeLevelSwitch(const std::string& name, ConfigReader& cfg, World& world) {
  const int32_t vessel = vesselRef(cfg, "tank", world, true);
  LevelSwitch::Params p;
  if (cfg.has("above") == cfg.has("below"))
    cfg.error(cfg.node().loc(), "needs exactly one of 'above' and 'below' (the threshold, e.g. above: 95 %)");
  p.above = cfg.has("above");
  p.threshold = readLevel(cfg, p.above ? "above" : "below", p.inPercent);
  if (cfg.has("hysteresis")) {
    bool hysteresisInPercent = p.inPercent;
    p.hysteresis = readLevel(cfg, "hysteresis", hysteresisInPercent);
    if (hysteresisInPercent != p.inPercent)
      cfg.error(cfg.node().find("hysteresis")->loc(), "'hysteresis' must be of the same kind as the threshold (% or a height)");
  }
  return std::make_unique<LevelSwitch>(name, static_cast<uint32_t>(vessel < 0 ? 0 : vessel), p);
}

}  // namespace virtcom::plant
