#include "plant/axis.hpp"

#include <cmath>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Axis::Axis(std::string name, Params params)
    : SequencedDevice(std::move(name), "axis", "targetPosition", ElemType::Lreal, "target position in mm (Table 2)"),
      p_(std::move(params)) {
  idlePowerW_ = p_.idlePowerW;
  posPort_ = addPort("actualPosition", ElemType::Lreal, PortDir::Out, "actual position in mm");
  velPort_ = addPort("actualVelocity", ElemType::Lreal, PortDir::Out, "actual velocity in mm/s (signed)");
  inPosPort_ = addPort("inPosition", ElemType::Bool, PortDir::Out, "at rest within in_position_window of the last target");
  pos_ = target_ = p_.homePosition;
}

void Axis::prepareLabels(World&, Trace& trace) {
  moveLabel_ = trace.internLabel("MoveTo");
  for (auto& np : p_.positions) np.label = trace.internLabel("MoveTo " + np.name);
}

uint32_t Axis::commandLabel(double command) const {
  const double target = command * 1e-3;
  if (!std::isfinite(target)) return moveLabel_;
  for (const auto& np : p_.positions)
    if (std::fabs(np.positionM - target) <= 1e-9) return np.label;
  return moveLabel_;
}

int32_t Axis::beginCommand(double command, int64_t startNs, const StepContext&) {
  commandEnergyJ_ = 0;
  const double target = command * 1e-3;
  if (!(target >= p_.minPosition - 1e-12 && target <= p_.maxPosition + 1e-12)) return code(DeviceError::OutOfLimits);
  target_ = target;
  const double distance = std::fabs(target - pos_);
  dir_ = target >= pos_ ? 1.0 : -1.0;
  profile_ = MotionProfile::plan(distance, p_.maxSpeed, p_.accel);
  startNs_ = startNs;
  endNs_ = startNs + secondsToNs(profile_.totalTime);
  moving_ = true;
  commandEnergyJ_ = p_.movingPowerW * distance / p_.maxSpeed + p_.accelPowerW * 2 * profile_.accelTime;
  return 0;
}

SequencedDevice::Progress Axis::advance(const StepContext& ctx, int64_t& atNs, int32_t&) {
  if (ctx.nowNs < endNs_) return Progress::Running;
  pos_ = target_;
  moving_ = false;
  atNs = endNs_;
  endNs_ = INT64_MAX;
  return Progress::Finished;
}

void Axis::writeOutputs(const StepContext& ctx) {
  double pos = pos_, vel = 0;
  if (moving_) {
    const double t = static_cast<double>(ctx.nowNs - startNs_) * 1e-9;
    pos = pos_ + dir_ * profile_.positionAt(t);
    vel = dir_ * profile_.speedAt(t);
  }
  ctx.bus.setReal(tag(posPort_), pos * 1e3);
  ctx.bus.setReal(tag(velPort_), vel * 1e3);
  ctx.bus.setBool(tag(inPosPort_), !moving_ && std::fabs(pos - target_) <= p_.window);
}

std::unique_ptr<Device> makeAxis(const std::string& name, ConfigReader& cfg, World&) {
  Axis::Params p;
  p.maxSpeed = cfg.requireQuantity("max_speed", Dimension::Speed);
  p.accel = cfg.requireQuantity("acceleration", Dimension::Acceleration);
  p.minPosition = cfg.requireQuantity("min_position", Dimension::Length);
  p.maxPosition = cfg.requireQuantity("max_position", Dimension::Length);
  p.window = cfg.optQuantity("in_position_window", Dimension::Length, 1e-4);
  p.homePosition = cfg.optQuantity("home_position", Dimension::Length, 0);
  p.idlePowerW = cfg.optQuantity("idle_power", Dimension::Power, 0);
  p.movingPowerW = cfg.optQuantity("moving_power", Dimension::Power, 0);
  p.accelPowerW = cfg.optQuantity("accel_power", Dimension::Power, 0);
  if (cfg.has("max_speed") && !(p.maxSpeed > 0)) cfg.error(cfg.node().find("max_speed")->loc(), "'max_speed' must be greater than 0");
  if (cfg.has("acceleration") && !(p.accel > 0))
    cfg.error(cfg.node().find("acceleration")->loc(), "'acceleration' must be greater than 0");
  if (cfg.has("min_position") && cfg.has("max_position") && p.minPosition > p.maxPosition)
    cfg.error(cfg.node().find("max_position")->loc(), "'max_position' must not be below 'min_position'");
  if (p.homePosition < p.minPosition || p.homePosition > p.maxPosition)
    cfg.error(cfg.has("home_position") ? cfg.node().find("home_position")->loc() : cfg.node().loc(),
              "'home_position' must lie within [min_position, max_position]");
  if (const ConfigNode* positions = mapChild(cfg, "positions", false)) {
    ConfigReader pr(*positions, cfg.diags(), "positions of axis '" + name + "'");
    for (const auto& [posName, node] : positions->entries()) {
      (void)node;
      Axis::NamedPosition np;
      np.name = posName;
      np.positionM = pr.requireQuantity(posName, Dimension::Length);
      p.positions.push_back(np);
    }
  }
  return std::make_unique<Axis>(name, std::move(p));
}

}  // namespace virtcom::plant
