#include "plant/heater.hpp"

#include <algorithm>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Heater::Heater(std::string name, uint32_t vessel, size_t feed, double powerW)
    : Device(std::move(name), "heater"), vessel_(vessel), feed_(feed), powerW_(powerW), periods_(powerW) {
  onPort_ = addPort("on", ElemType::Bool, PortDir::In, "heat while true");
}

void Heater::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  periods_.prepare(trace, "Heating");
}

void Heater::step(const StepContext& ctx) {
  const bool on = ctx.bus.getBool(tag(onPort_));
  ctx.world.vesselAt(vessel_).feeds[feed_].set(ctx.nowNs, Feed{0, 0, on ? powerW_ : 0});
  periods_.update(ctx.trace, traceIndex(), on, ctx.nowNs);
}

void Heater::finish(int64_t endNs, Trace& trace) { periods_.finish(trace, traceIndex(), endNs); }

std::unique_ptr<Device> makeHeater(const std::string& name, ConfigReader& cfg, World& world) {
  // Without a tank (a reported mistake) the device is built but never stepped.
  const int32_t vessel = vesselRef(cfg, "tank", world, true);
  const size_t feed = vessel >= 0 ? world.addFeed(static_cast<uint32_t>(vessel)) : 0;
  const double powerW = requirePositive(cfg, "power", Dimension::Power);
  return std::make_unique<Heater>(name, static_cast<uint32_t>(std::max(vessel, 0)), feed, powerW);
}

}  // namespace virtcom::plant
