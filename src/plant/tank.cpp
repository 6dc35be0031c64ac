#include "plant/tank.hpp"

#include <algorithm>
#include <cmath>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Tank::Tank(std::string name, uint32_t vessel, Params params)
    : Device(std::move(name), "tank"), p_(params), vessel_(vessel) {
  volumePort_ = addPort("volume", ElemType::Real, PortDir::Out, "liquid in the tank (l)");
  levelPort_ = addPort("level", ElemType::Real, PortDir::Out, "level in % of the capacity");
  levelMmPort_ = addPort("level_mm", ElemType::Real, PortDir::Out, "level above the bottom (mm)");
  temperaturePort_ = addPort("temperature", ElemType::Real, PortDir::Out, "liquid temperature (°C)");
  overflowPort_ = addPort("overflow", ElemType::Bool, PortDir::Out, "the tank is full and spills what flows in");
}

void Tank::integrate(Vessel& v, int64_t nowNs, double dtS) {
  double inM3 = 0, inHeatM3C = 0, outM3 = 0, heatJ = 0;
  for (const FeedSlot& slot : v.feeds) {
    const Feed& f = slot.heldUntil(nowNs);
    if (f.flowM3s > 0) {
      inM3 += f.flowM3s * dtS;
      inHeatM3C += f.flowM3s * dtS * f.inletC;
    } else {
      outM3 -= f.flowM3s * dtS;
    }
    heatJ += f.heatW * dtS;
  }
  if (inM3 > 0) {
    v.temperatureC = (v.volumeM3 * v.temperatureC + inHeatM3C) / (v.volumeM3 + inM3);
    v.volumeM3 += inM3;
  }
  v.volumeM3 = std::max(v.volumeM3 - outM3, 0.0);
  overflow_ = v.volumeM3 > p_.capacityM3;
  v.volumeM3 = std::min(v.volumeM3, p_.capacityM3);
  if (v.volumeM3 > 0) {
    // the loss as exact exponential decay towards the ambient: stable for any tick and volume
    const double heatCapacityJPerK = p_.densityKgM3 * v.volumeM3 * p_.specificHeatJPerKgK;
    v.temperatureC += heatJ / heatCapacityJPerK;
    v.temperatureC = p_.ambientC + (v.temperatureC - p_.ambientC) * std::exp(-p_.heatLossWPerK * dtS / heatCapacityJPerK);
  }
}

void Tank::step(const StepContext& ctx) {
  Vessel& v = ctx.world.vesselAt(vessel_);
  if (!started_) {
    started_ = true;
    v.capacityM3 = p_.capacityM3;
    v.heightM = p_.heightM;
    v.volumeM3 = p_.initialRatio * p_.capacityM3;
    v.temperatureC = p_.initialC;
  } else {
    integrate(v, ctx.nowNs, static_cast<double>(ctx.nowNs - lastNs_) * 1e-9);
  }
  lastNs_ = ctx.nowNs;
  ctx.bus.setReal(tag(volumePort_), v.volumeM3 * 1e3);
  ctx.bus.setReal(tag(levelPort_), v.levelRatio() * 100);
  ctx.bus.setReal(tag(levelMmPort_), v.levelM() * 1e3);
  ctx.bus.setReal(tag(temperaturePort_), v.temperatureC);
  ctx.bus.setBool(tag(overflowPort_), overflow_);
}

std::unique_ptr<Device> makeTank(const std::string& name, ConfigReader& cfg, World& world) {
  Tank::Params p;
  p.capacityM3 = requirePositive(cfg, "capacity", Dimension::Volume);
  p.heightM = optPositive(cfg, "height", Dimension::Length, 1.0);
  p.initialRatio = cfg.optQuantity("initial_level", Dimension::Ratio, 0);
  if (p.initialRatio < 0 || p.initialRatio > 1)
    cfg.error(cfg.node().find("initial_level")->loc(), "'initial_level' must be from 0 % to 100 %");
  p.initialC = cfg.optQuantity("initial_temperature", Dimension::Temperature, 20);
  p.ambientC = cfg.optQuantity("ambient_temperature", Dimension::Temperature, 20);
  p.heatLossWPerK = cfg.optQuantity("heat_loss", Dimension::ThermalConductance, 0);
  if (p.heatLossWPerK < 0) cfg.error(cfg.node().find("heat_loss")->loc(), "'heat_loss' must not be negative");
  p.densityKgM3 = optPositive(cfg, "density", Dimension::Density, 1000);
  p.specificHeatJPerKgK = optPositive(cfg, "specific_heat", Dimension::SpecificHeat, 4186);
  // The tank's vessel is named after the device; the devices acting on it name it so.
  const uint32_t vessel = world.vessel(name, cfg.node().loc());
  world.vesselAt(vessel).defined = true;
  return std::make_unique<Tank>(name, vessel, p);
}

}  // namespace virtcom::plant
