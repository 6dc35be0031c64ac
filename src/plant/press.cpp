#include "plant/press.hpp"

#include <algorithm>
#include <cmath>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

Press::Press(std::string name, Params params)
    : SequencedDevice(std::move(name), "press", "programNumber", ElemType::Int, "number of the press program (Table 2)"),
      p_(std::move(params)) {
  idlePowerW_ = p_.idlePowerW;
  forcePort_ = addPort("actualForce", ElemType::Lreal, PortDir::Out, "press force in N");
  positionPort_ = addPort("position", ElemType::Lreal, PortDir::Out, "ram position in mm (0 = top)");
}

void Press::prepareLabels(World&, Trace& trace) {
  for (auto& prog : p_.programs) prog.label = trace.internLabel(prog.name);
}

const Press::Program* Press::find(double command) const {
  const double n = std::nearbyint(command);
  for (const auto& prog : p_.programs)
    if (prog.number == n) return &prog;
  return nullptr;
}

uint32_t Press::commandLabel(double command) const {
  const Program* prog = find(command);
  return prog ? prog->label : kNoLabel;
}

int32_t Press::beginCommand(double command, int64_t startNs, const StepContext& ctx) {
  commandEnergyJ_ = 0;
  prog_ = find(command);
  if (!ctx.world.hasFact(p_.insertFact)) return code(DeviceError::NoInsert);
  for (uint32_t f : prog_->requires_)
    if (!ctx.world.hasFact(f)) return code(DeviceError::PreconditionNotMet);
  startNs_ = startNs;
  running_ = true;
  commandEnergyJ_ = p_.pressPowerW * static_cast<double>(prog_->pressNs + prog_->holdNs) * 1e-9;
  return 0;
}

int64_t Press::endNs() const {
  return startNs_ + prog_->approachNs + prog_->pressNs + prog_->holdNs + prog_->returnNs;
}

// The next phase boundary, or 0 inside a phase whose output ramps (position during approach and
// return, force during press): writeOutputs gives those a new value every tick.
int64_t Press::modelNextEventNs() const {
  if (!running_) return INT64_MAX;
  const int64_t pressStart = startNs_ + prog_->approachNs, holdStart = pressStart + prog_->pressNs;
  const int64_t returnStart = holdStart + prog_->holdNs;
  const bool stroke = p_.strokeM != 0;
  if (outputsNs_ < pressStart) return stroke ? 0 : pressStart;
  if (outputsNs_ < holdStart) return prog_->forceN != 0 ? 0 : holdStart;
  if (outputsNs_ < returnStart) return returnStart;
  return stroke ? 0 : endNs();
}

SequencedDevice::Progress Press::advance(const StepContext& ctx, int64_t& atNs, int32_t&) {
  const int64_t end = endNs();
  if (ctx.nowNs < end) return Progress::Running;
  for (uint32_t f : prog_->sets) ctx.world.setFact(f, true);
  for (uint32_t f : prog_->clears) ctx.world.setFact(f, false);
  running_ = false;
  atNs = end;
  return Progress::Finished;
}

void Press::writeOutputs(const StepContext& ctx) {
  outputsNs_ = ctx.nowNs;
  double force = 0, position = 0;
  if (running_) {
    const int64_t t = ctx.nowNs - startNs_;
    const int64_t pressStart = prog_->approachNs, holdStart = pressStart + prog_->pressNs;
    const int64_t returnStart = holdStart + prog_->holdNs, end = returnStart + prog_->returnNs;
    auto frac = [](int64_t part, int64_t whole) { return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 1.0; };
    if (t < pressStart) {
      position = p_.strokeM * frac(t, prog_->approachNs);
    } else if (t < holdStart) {
      position = p_.strokeM;
      force = prog_->forceN * frac(t - pressStart, prog_->pressNs);
    } else if (t < returnStart) {
      position = p_.strokeM;
      force = prog_->forceN;
    } else if (t < end) {
      position = p_.strokeM * (1.0 - frac(t - returnStart, prog_->returnNs));
    }
  }
  ctx.bus.setReal(tag(forcePort_), force);
  ctx.bus.setReal(tag(positionPort_), position * 1e3);
}

std::unique_ptr<Device> makePress(const std::string& name, ConfigReader& cfg, World& world) {
  Press::Params p;
  p.insertFact = world.fact(cfg.optString("insert_fact", "insertLocked"));
  p.strokeM = cfg.optQuantity("stroke", Dimension::Length, 0);
  p.idlePowerW = cfg.optQuantity("idle_power", Dimension::Power, 0);
  p.pressPowerW = cfg.optQuantity("press_power", Dimension::Power, 0);
  if (const ConfigNode* programs = mapChild(cfg, "programs", true)) {
    for (const auto& [key, node] : programs->entries()) {
      Press::Program prog;
      parseCommandNumber(cfg, key, programs->keyLoc(key), prog.number);
      for (const auto& other : p.programs)
        if (other.number == prog.number && prog.number != 0) cfg.error(node.loc(), "program number " + key + " is defined twice");
      ConfigReader r(node, cfg.diags(), "program " + key + " of press '" + name + "'");
      prog.name = r.requireString("name");
      prog.approachNs = optDurationNs(r, "approach_time", 0);
      prog.pressNs = requireDurationNs(r, "press_time");
      prog.holdNs = optDurationNs(r, "hold_time", 0);
      prog.returnNs = optDurationNs(r, "return_time", 0);
      prog.forceN = r.requireQuantity("force", Dimension::Force);
      prog.requires_ = optFactList(r, "requires", world);
      prog.sets = optFactList(r, "sets", world);
      prog.clears = optFactList(r, "clears", world);
      r.rejectUnknownKeys();
      p.programs.push_back(std::move(prog));
    }
    std::stable_sort(p.programs.begin(), p.programs.end(), [](const auto& a, const auto& b) { return a.number < b.number; });
  }
  return std::make_unique<Press>(name, std::move(p));
}

}  // namespace virtcom::plant
