#pragma once
// A linear positioning axis (the seed's Bosch Rexroth IntraDrive X/Y table axes). The command
// is the target position itself (targetPosition, LREAL mm): each execute moves there from the
// current position with a trapezoidal/triangular profile; done when in position. A target outside
// [min_position, max_position] is refused with error 30 and the axis does not move.
// Activity labels: "MoveTo", or "MoveTo <name>" when the target equals a named `positions:`
// entry (labels interned at prepare, so no string is built per command).
// Energy: idle_power over the run; per move moving_power x distance/max_speed +
// accel_power x 2 x accelerationTime.
#include <memory>
#include <string>
#include <vector>

#include "plant/motion_profile.hpp"
#include "plant/sequenced_device.hpp"

namespace virtcom::plant {

class Axis final : public SequencedDevice {
 public:
  struct NamedPosition {
    std::string name;
    double positionM = 0;
    uint32_t label = 0;
  };
  struct Params {
    double maxSpeed = 0, accel = 0;           // m/s, m/s^2
    double minPosition = 0, maxPosition = 0;  // m
    double window = 1e-4;                     // m
    double homePosition = 0;                  // m
    double idlePowerW = 0, movingPowerW = 0, accelPowerW = 0;
    std::vector<NamedPosition> positions;
  };

  Axis(std::string name, Params params);
  const Params& params() const { return p_; }
  bool changesParameter(std::string_view) const override { return true; }
  void swapParameters(Device& edited) override {
    const NamedPosition* none = nullptr;  // a move runs to its target, not to an entry
    swapKeepingLabels(p_, static_cast<Axis&>(edited).p_, &Params::positions, none);
  }
  double positionM() const { return pos_; }

 protected:
  uint32_t commandLabel(double command) const override;
  int32_t beginCommand(double command, int64_t startNs, const StepContext& ctx) override;
  Progress advance(const StepContext& ctx, int64_t& atNs, int32_t& error) override;
  double commandEnergyJ() const override { return commandEnergyJ_; }
  int64_t modelNextEventNs() const override { return moving_ ? 0 : endNs_; }  // position ramps
  void writeOutputs(const StepContext& ctx) override;
  void prepareLabels(World& world, Trace& trace) override;

 private:
  Params p_;
  size_t posPort_ = 0, velPort_ = 0, inPosPort_ = 0;
  uint32_t moveLabel_ = 0;
  double pos_ = 0;     // m, at rest (or the start of the running move)
  double target_ = 0;  // m
  double dir_ = 0;     // +1 / -1
  int64_t startNs_ = 0;
  int64_t endNs_ = INT64_MAX;
  bool moving_ = false;
  MotionProfile profile_;
  double commandEnergyJ_ = 0;
};

std::unique_ptr<Device> makeAxis(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
