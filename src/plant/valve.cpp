#include "plant/valve.hpp"

#include <algorithm>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Valve::Valve(std::string name, Transfer transfer, int64_t travelNs)
    : Device(std::move(name), "valve"), transfer_(transfer), travelNs_(travelNs) {
  openPort_ = addPort("open", ElemType::Bool, PortDir::In, "open the valve while true");
  openedPort_ = addPort("opened", ElemType::Bool, PortDir::Out, "fully open");
  closedPort_ = addPort("closed", ElemType::Bool, PortDir::Out, "fully closed");
}

void Valve::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  periods_.prepare(trace, "Open");
}

void Valve::step(const StepContext& ctx) {
  const double target = ctx.bus.getBool(tag(openPort_)) ? 1.0 : 0.0;
  if (travelNs_ <= 0) {
    opening_ = target;
  } else {
    const double travel = static_cast<double>(ctx.nowNs - lastNs_) / static_cast<double>(travelNs_);
    opening_ = target > opening_ ? std::min(opening_ + travel, target) : std::max(opening_ - travel, target);
  }
  lastNs_ = ctx.nowNs;
  transfer_.apply(ctx.world, ctx.nowNs, opening_);
  ctx.bus.setBool(tag(openedPort_), opening_ >= 1.0);
  ctx.bus.setBool(tag(closedPort_), opening_ <= 0.0);
  periods_.update(ctx.trace, traceIndex(), opening_ > 0.0, ctx.nowNs);
}

void Valve::finish(int64_t endNs, Trace& trace) { periods_.finish(trace, traceIndex(), endNs); }

std::unique_ptr<Device> makeValve(const std::string& name, ConfigReader& cfg, World& world) {
  Transfer transfer = readTransfer(cfg, world);
  const int64_t travelNs = optDurationNs(cfg, "travel_time", 0);
  return std::make_unique<Valve>(name, transfer, travelNs);
}

}  // namespace virtcom::plant
