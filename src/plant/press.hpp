#pragma once
// A servo press (the seed's Coretec CS20-350B): numbered programs, each approach -> press ->
// hold -> return with fixed times. A program starts only if the insert fact (`insert_fact`,
// default insertLocked) is true (else error 40) and its `requires:` facts are true (else 20);
// its `sets:`/`clears:` facts change when it ends.
// actualForce (N): 0 during approach and return, ramps linearly to `force` during press,
// holds it during hold. position (mm): 0 -> stroke during approach, stroke during press and
// hold, stroke -> 0 during return (all 0 if no stroke is configured).
// Energy: idle_power over the run + press_power x (press_time + hold_time) per program.
#include <memory>
#include <string>
#include <vector>

#include "plant/sequenced_device.hpp"

namespace virtcom::plant {

class Press final : public SequencedDevice {
 public:
  struct Program {
    int32_t number = 0;
    std::string name;
    int64_t approachNs = 0, pressNs = 0, holdNs = 0, returnNs = 0;
    double forceN = 0;
    std::vector<uint32_t> requires_, sets, clears;
    uint32_t label = 0;
  };
  struct Params {
    uint32_t insertFact = 0;
    double strokeM = 0;
    double idlePowerW = 0, pressPowerW = 0;
    std::vector<Program> programs;  // sorted by number
  };

  Press(std::string name, Params params);
  const Params& params() const { return p_; }
  bool changesParameter(std::string_view) const override { return true; }
  void swapParameters(Device& edited) override { swapKeepingLabels(p_, static_cast<Press&>(edited).p_, &Params::programs, prog_); }

 protected:
  uint32_t commandLabel(double command) const override;
  int32_t beginCommand(double command, int64_t startNs, const StepContext& ctx) override;
  Progress advance(const StepContext& ctx, int64_t& atNs, int32_t& error) override;
  double commandEnergyJ() const override { return commandEnergyJ_; }
  int64_t modelNextEventNs() const override;
  void writeOutputs(const StepContext& ctx) override;
  void prepareLabels(World& world, Trace& trace) override;

 private:
  const Program* find(double command) const;
  int64_t endNs() const;
  Params p_;
  size_t forcePort_ = 0, positionPort_ = 0;
  const Program* prog_ = nullptr;
  int64_t startNs_ = 0;
  int64_t outputsNs_ = 0;  // when writeOutputs last ran
  bool running_ = false;
  double commandEnergyJ_ = 0;
};

std::unique_ptr<Device> makePress(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
