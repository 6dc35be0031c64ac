#include "plant/robot.hpp"

#include <algorithm>
#include <cmath>

namespace virtcom::plant {

Robot::Robot(std::string name, Params params) : SequencedDevice(std::move(name), "robot", "procedureNumber", ElemType::Int,
                                                                "number of the procedure to run (Table 2)"),
                                                p_(std::move(params)) {
  idlePowerW_ = p_.idlePowerW;
  xPort_ = addPort("actualX", ElemType::Lreal, PortDir::Out, "TCP x position in mm");
  yPort_ = addPort("actualY", ElemType::Lreal, PortDir::Out, "TCP y position in mm");
  zPort_ = addPort("actualZ", ElemType::Lreal, PortDir::Out, "TCP z position in mm");
  toolPort_ = addPort("toolAttached", ElemType::Int, PortDir::Out, "attached tool: index+1 in `tools:`, 0 = none");
  location_ = static_cast<int32_t>(p_.home);
  tool_ = p_.initialTool;
  if (!p_.locations.empty()) std::copy_n(p_.locations[p_.home].pos, 3, pos_);
}

double Robot::payloadKg() const { return heldMassKg_ + (tool_ >= 0 ? p_.tools[static_cast<size_t>(tool_)].massKg : 0.0); }

void Robot::prepareLabels(World& world, Trace& trace) {
  for (auto& proc : p_.procedures) proc.label = trace.internLabel(proc.name);
  idleLabel_ = trace.internLabel("Idle");
  if (!p_.locations.empty() && p_.locations[p_.home].zone >= 0)
    world.enterZone(static_cast<uint32_t>(p_.locations[p_.home].zone), traceIndex(), idleLabel_, 0);
}

const Robot::Procedure* Robot::findProcedure(double command) const {
  const double n = std::nearbyint(command);
  auto it = std::lower_bound(p_.procedures.begin(), p_.procedures.end(), n,
                             [](const Procedure& p, double v) { return p.number < v; });
  return it != p_.procedures.end() && it->number == n ? &*it : nullptr;
}

uint32_t Robot::commandLabel(double command) const {
  const Procedure* proc = findProcedure(command);
  return proc ? proc->label : kNoLabel;
}

int32_t Robot::beginCommand(double command, int64_t startNs, const StepContext& ctx) {
  proc_ = findProcedure(command);
  commandEnergyJ_ = 0;
  // A robot standing in a zone is now doing this procedure there (collision labels).
  if (const int32_t zone = p_.locations[static_cast<size_t>(location_)].zone; zone >= 0)
    ctx.world.enterZone(static_cast<uint32_t>(zone), traceIndex(), proc_->label, startNs);
  stepIndex_ = proc_->firstStep;
  stepEndNs_ = startNs;
  if (proc_->stepCount == 0) return 0;
  return beginStep(startNs, ctx);
}

SequencedDevice::Progress Robot::advance(const StepContext& ctx, int64_t& atNs, int32_t& error) {
  const uint32_t endStep = proc_->firstStep + proc_->stepCount;
  while (stepEndNs_ <= ctx.nowNs) {
    if (stepIndex_ < endStep) {
      completeStep(ctx);
      ++stepIndex_;
    }
    if (stepIndex_ == endStep) {
      atNs = stepEndNs_;
      stepEndNs_ = INT64_MAX;
      return Progress::Finished;
    }
    if (int32_t e = beginStep(stepEndNs_, ctx); e != 0) {
      error = e;
      stepEndNs_ = INT64_MAX;
      return Progress::Failed;
    }
  }
  return Progress::Running;
}

int32_t Robot::beginStep(int64_t t, const StepContext& ctx) {
  const Step& s = p_.steps[stepIndex_];
  stepStartNs_ = t;
  int64_t duration = 0;
  const Tool* tool = tool_ >= 0 ? &p_.tools[static_cast<size_t>(tool_)] : nullptr;
  switch (s.op) {
    case Op::Move: {
      const Location& to = p_.locations[s.arg];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) {
        from_[i] = pos_[i];
        dir_[i] = to.pos[i] - pos_[i];
        d2 += dir_[i] * dir_[i];
      }
      const double distance = std::sqrt(d2);
      for (double& c : dir_) c = distance > 0 ? c / distance : 0;
      profile_ = MotionProfile::plan(distance, p_.maxSpeed, p_.accel);
      duration = secondsToNs(profile_.totalTime);
      commandEnergyJ_ += (1 + payloadKg() / p_.payloadCapacityKg) *
                         (p_.movingPowerW * distance / p_.maxSpeed + p_.accelPowerW * 2 * profile_.accelTime);
      if (to.zone >= 0) ctx.world.enterZone(static_cast<uint32_t>(to.zone), traceIndex(), proc_->label, t);
      break;
    }
    case Op::Attach: {
      const Tool& want = p_.tools[s.arg];
      if (tool || (want.magazine >= 0 && want.magazine != location_)) return code(DeviceError::WrongTool);
      duration = p_.toolChangeNs;
      break;
    }
    case Op::Detach:
      if (!tool || heldPart_ >= 0 || (tool->magazine >= 0 && tool->magazine != location_))
        return code(DeviceError::WrongTool);
      duration = p_.toolChangeNs;
      break;
    case Op::Grip: {
      const Part& part = p_.parts[s.arg];
      if (!tool || !isGripper(tool->kind) || heldPart_ >= 0 || (part.tool >= 0 && part.tool != tool_))
        return code(DeviceError::WrongTool);
      if (!ctx.world.hasFact(part.fact)) return code(DeviceError::PartMissing);
      duration = tool->closeNs;
      break;
    }
    case Op::Release:
      if (heldPart_ != static_cast<int32_t>(s.arg)) return code(DeviceError::PartMissing);
      duration = tool ? tool->openNs : 0;
      break;
    case Op::Screw:
      if (!tool || tool->kind != ToolKind::Screwer) return code(DeviceError::WrongTool);
      if (!ctx.world.hasFact(s.arg)) return code(DeviceError::NoStud);
      duration = tool->rundownNs;
      break;
    case Op::Wait:
      duration = s.ns;
      break;
    case Op::Require:
      if (!ctx.world.hasFact(s.arg)) return code(DeviceError::PreconditionNotMet);
      break;
    case Op::Set:
    case Op::Clear:
      break;
  }
  stepEndNs_ = t + duration;
  return 0;
}

void Robot::completeStep(const StepContext& ctx) {
  const Step& s = p_.steps[stepIndex_];
  switch (s.op) {
    case Op::Move: {
      const Location& to = p_.locations[s.arg];
      std::copy_n(to.pos, 3, pos_);
      const int32_t oldZone = p_.locations[static_cast<size_t>(location_)].zone;
      if (oldZone >= 0 && oldZone != to.zone) ctx.world.leaveZone(static_cast<uint32_t>(oldZone), traceIndex());
      location_ = static_cast<int32_t>(s.arg);
      break;
    }
    case Op::Attach: tool_ = static_cast<int32_t>(s.arg); break;
    case Op::Detach: tool_ = -1; break;
    case Op::Grip:
      ctx.world.setFact(p_.parts[s.arg].fact, false);
      heldPart_ = static_cast<int32_t>(s.arg);
      heldMassKg_ = p_.parts[s.arg].massKg;
      break;
    case Op::Release:
      heldPart_ = -1;
      heldMassKg_ = 0;
      break;
    case Op::Screw: ctx.world.setFact(s.arg2, true); break;
    case Op::Set: ctx.world.setFact(s.arg, true); break;
    case Op::Clear: ctx.world.setFact(s.arg, false); break;
    case Op::Wait:
    case Op::Require: break;
  }
}

void Robot::writeOutputs(const StepContext& ctx) {
  double p[3] = {pos_[0], pos_[1], pos_[2]};
  if (busy() && stepEndNs_ != INT64_MAX && p_.steps[stepIndex_].op == Op::Move && ctx.nowNs < stepEndNs_) {
    const double s = profile_.positionAt(static_cast<double>(ctx.nowNs - stepStartNs_) * 1e-9);
    for (int i = 0; i < 3; ++i) p[i] = from_[i] + dir_[i] * s;
  }
  ctx.bus.setReal(tag(xPort_), p[0] * 1e3);
  ctx.bus.setReal(tag(yPort_), p[1] * 1e3);
  ctx.bus.setReal(tag(zPort_), p[2] * 1e3);
  ctx.bus.setInt(tag(toolPort_), tool_ + 1);
}

}  // namespace virtcom::plant
