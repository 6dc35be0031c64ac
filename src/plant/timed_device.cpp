#include "plant/timed_device.hpp"

#include <cmath>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

TimedDevice::TimedDevice(std::string name, Params params)
    : SequencedDevice(std::move(name), "timed", params.commandPort, ElemType::Int, "number of the command to run"),
      p_(std::move(params)) {
  idlePowerW_ = p_.idlePowerW;
}

void TimedDevice::prepareLabels(World&, Trace& trace) {
  for (auto& c : p_.commands) c.label = trace.internLabel(c.name);
}

const TimedDevice::Command* TimedDevice::find(double command) const {
  const double n = std::nearbyint(command);
  for (const auto& c : p_.commands)
    if (c.number == n) return &c;
  return nullptr;
}

uint32_t TimedDevice::commandLabel(double command) const {
  const Command* c = find(command);
  return c ? c->label : kNoLabel;
}

int32_t TimedDevice::beginCommand(double command, int64_t startNs, const StepContext& ctx) {
  commandEnergyJ_ = 0;
  cmd_ = find(command);
  for (uint32_t f : cmd_->requires_)
    if (!ctx.world.hasFact(f)) return code(DeviceError::PreconditionNotMet);
  endNs_ = startNs + cmd_->durationNs;
  commandEnergyJ_ = p_.busyPowerW * static_cast<double>(cmd_->durationNs) * 1e-9;
  return 0;
}

SequencedDevice::Progress TimedDevice::advance(const StepContext& ctx, int64_t& atNs, int32_t&) {
  if (ctx.nowNs < endNs_) return Progress::Running;
  for (uint32_t f : cmd_->sets) ctx.world.setFact(f, true);
  for (uint32_t f : cmd_->clears) ctx.world.setFact(f, false);
  atNs = endNs_;
  endNs_ = INT64_MAX;
  return Progress::Finished;
}

std::unique_ptr<Device> makeTimed(const std::string& name, ConfigReader& cfg, World& world) {
  TimedDevice::Params p;
  p.commandPort = cfg.optString("command_port", "programNumber");
  if (p.commandPort.empty() || p.commandPort == "execute" || p.commandPort == "done" || p.commandPort == "error" ||
      p.commandPort == "busy")
    cfg.error(cfg.node().find("command_port")->loc(), "'command_port' must be a new port name such as programNumber");
  p.idlePowerW = cfg.optQuantity("idle_power", Dimension::Power, 0);
  p.busyPowerW = cfg.optQuantity("busy_power", Dimension::Power, 0);
  if (const ConfigNode* commands = mapChild(cfg, "commands", true)) {
    for (const auto& [key, node] : commands->entries()) {
      TimedDevice::Command c;
      parseCommandNumber(cfg, key, commands->keyLoc(key), c.number);
      for (const auto& other : p.commands)
        if (other.number == c.number && c.number != 0) cfg.error(node.loc(), "command number " + key + " is defined twice");
      ConfigReader r(node, cfg.diags(), "command " + key + " of '" + name + "'");
      c.name = r.requireString("name");
      c.durationNs = requireDurationNs(r, "duration");
      c.requires_ = optFactList(r, "requires", world);
      c.sets = optFactList(r, "sets", world);
      c.clears = optFactList(r, "clears", world);
      r.rejectUnknownKeys();
      p.commands.push_back(std::move(c));
    }
  }
  return std::make_unique<TimedDevice>(name, std::move(p));
}

}  // namespace virtcom::plant
