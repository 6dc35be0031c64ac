#pragma once
// A generic timed device: numbered commands that take a fixed `duration`, need their
// `requires:` facts (else error 20 at the start) and set/clear facts when they end. Models any
// device of the cell that is not worth a dedicated class (a clamp, a feeder, an insert lock).
// The command port name is configurable (`command_port`, default programNumber, INT).
// Energy: idle_power over the run + busy_power x duration per command.
#include <memory>
#include <string>
#include <vector>

#include "plant/sequenced_device.hpp"

namespace virtcom::plant {

class TimedDevice final : public SequencedDevice {
 public:
  struct Command {
    int32_t number = 0;
    std::string name;
    int64_t durationNs = 0;
    std::vector<uint32_t> requires_, sets, clears;
    uint32_t label = 0;
  };
  struct Params {
    std::string commandPort = "programNumber";
    double idlePowerW = 0, busyPowerW = 0;
    std::vector<Command> commands;
  };

  TimedDevice(std::string name, Params params);
  bool changesParameter(std::string_view) const override { return true; }
  void swapParameters(Device& edited) override { swapKeepingLabels(p_, static_cast<TimedDevice&>(edited).p_, &Params::commands, cmd_); }

 protected:
  uint32_t commandLabel(double command) const override;
  int32_t beginCommand(double command, int64_t startNs, const StepContext& ctx) override;
  Progress advance(const StepContext& ctx, int64_t& atNs, int32_t& error) override;
  double commandEnergyJ() const override { return commandEnergyJ_; }
  int64_t modelNextEventNs() const override { return endNs_; }
  void writeOutputs(const StepContext&) override {}
  void prepareLabels(World& world, Trace& trace) override;

 private:
  const Command* find(double command) const;
  Params p_;
  const Command* cmd_ = nullptr;
  int64_t endNs_ = INT64_MAX;
  double commandEnergyJ_ = 0;
};

std::unique_ptr<Device> makeTimed(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
