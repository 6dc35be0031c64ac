#include "plant/sequenced_device.hpp"

namespace virtcom::plant {

SequencedDevice::SequencedDevice(std::string name, std::string type, std::string commandPort, ElemType commandType,
                                 std::string commandDoc)
    : Device(std::move(name), std::move(type)) {
  addPort(std::move(commandPort), commandType, PortDir::In, std::move(commandDoc));
  addPort("execute", ElemType::Bool, PortDir::In, "starts the command (level, read only while idle)");
  addPort("done", ElemType::Bool, PortDir::Out, "command finished; held until execute drops");
  addPort("error", ElemType::Int, PortDir::Out, "error code, 0 = none; held until execute drops");
  addPort("busy", ElemType::Bool, PortDir::Out, "a command is running");
}

void SequencedDevice::prepare(World& world, Trace& trace) {
  Device::prepare(world, trace);
  unknownLabel_ = trace.internLabel("UnknownCommand");
  prepareLabels(world, trace);
}

void SequencedDevice::step(const StepContext& ctx) {
  execute_ = ctx.bus.getBool(tag(kExecutePort));
  lastStepNs_ = ctx.nowNs;
  switch (phase_) {
    case Phase::Idle:
      if (execute_) startCommand(ctx);
      break;
    case Phase::Running:
      progress(ctx);
      break;
    case Phase::Delaying:
      if (ctx.nowNs >= delayEndNs_) complete(ctx);
      break;
    case Phase::WaitDrop:
      if (!execute_) {
        done_ = false;
        error_ = 0;
        phase_ = Phase::Idle;
      }
      break;
  }
  ctx.bus.setBool(tag(kDonePort), done_);
  ctx.bus.setInt(tag(kErrorPort), error_);
  ctx.bus.setBool(tag(kBusyPort), busy());
  writeOutputs(ctx);
}

void SequencedDevice::startCommand(const StepContext& ctx) {
  ++commandCount_;
  const double command = ctx.bus.getNumber(tag(kCommandPort));
  const uint32_t label = commandLabel(command);
  startNs_ = ctx.nowNs;
  activity_ = ctx.trace.beginActivity(traceIndex(), label == kNoLabel ? unknownLabel_ : label, ctx.nowNs);
  if (label == kNoLabel) return fail(ctx, code(DeviceError::UnknownCommand), 0);
  if (faults_.errorCode != 0 && (faults_.errorAtCommand == 0 || faults_.errorAtCommand == commandCount_))
    return fail(ctx, faults_.errorCode, 0);
  if (int32_t refused = beginCommand(command, ctx.nowNs, ctx); refused != 0) return fail(ctx, refused, 0);
  phase_ = Phase::Running;
  progress(ctx);
}

void SequencedDevice::progress(const StepContext& ctx) {
  int64_t endNs = 0;
  int32_t error = 0;
  switch (advance(ctx, endNs, error)) {
    case Progress::Running:
      return;
    case Progress::Failed:
      return fail(ctx, error, commandEnergyJ());
    case Progress::Finished:
      delayEndNs_ = endNs + faults_.extraDelayNs;
      if (ctx.nowNs >= delayEndNs_) return complete(ctx);
      phase_ = Phase::Delaying;
      return;
  }
}

void SequencedDevice::complete(const StepContext& ctx) {
  const double energy = commandEnergyJ();
  ctx.trace.endActivity(activity_, ctx.nowNs, energy, 0);
  energySumJ_ += energy;
  busyNs_ += ctx.nowNs - startNs_;
  done_ = !faults_.doneStuck;
  phase_ = Phase::WaitDrop;
}

void SequencedDevice::fail(const StepContext& ctx, int32_t error, double energyJ) {
  ctx.trace.endActivity(activity_, ctx.nowNs, energyJ, error);
  energySumJ_ += energyJ;
  busyNs_ += ctx.nowNs - startNs_;
  error_ = error;
  done_ = false;
  phase_ = Phase::WaitDrop;
}

int64_t SequencedDevice::nextEventNs() const {
  switch (phase_) {
    case Phase::Idle: return execute_ ? lastStepNs_ : INT64_MAX;
    case Phase::Running: return modelNextEventNs();
    case Phase::Delaying: return delayEndNs_;
    case Phase::WaitDrop: return execute_ ? INT64_MAX : lastStepNs_;  // drops done at the next tick
  }
  return INT64_MAX;
}

void SequencedDevice::finish(int64_t endNs, Trace& trace) {
  DeviceTotals& t = trace.totals[traceIndex()];
  t.energyJ = idlePowerW_ * static_cast<double>(endNs) * 1e-9 + energySumJ_;
  t.busyNs = busyNs_;
  if (busy()) {
    t.energyJ += commandEnergyJ();
    t.busyNs += endNs - startNs_;
  }
}

}  // namespace virtcom::plant
