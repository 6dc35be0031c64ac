#include "plant/pump.hpp"

namespace virtcom::plant {

Pump::Pump(std::string name, Transfer transfer, double powerW)
    : Device(std::move(name), "pump"), transfer_(transfer), periods_(powerW) {
  runPort_ = addPort("run", ElemType::Bool, PortDir::In, "run the pump while true");
  runningPort_ = addPort("running", ElemType::Bool, PortDir::Out, "the pump runs");
}

void Pump::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  periods_.prepare(trace, "Running");
}

void Pump::step(const StepContext& ctx) {
  const bool run = ctx.bus.getBool(tag(runPort_));
  transfer_.apply(ctx.world, ctx.nowNs, run ? 1.0 : 0.0);
  ctx.bus.setBool(tag(runningPort_), run);
  periods_.update(ctx.trace, traceIndex(), run, ctx.nowNs);
}

void Pump::finish(int64_t endNs, Trace& trace) { periods_.finish(trace, traceIndex(), endNs); }

std::unique_ptr<Device> makePump(const std::string& name, ConfigReader& cfg, World& world) {
  Transfer transfer = readTransfer(cfg, world);
  const double powerW = cfg.optQuantity("power", Dimension::Power, 0);
  return std::make_unique<Pump>(name, transfer, powerW);
}

}  // namespace virtcom::plant
