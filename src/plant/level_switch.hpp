#pragma once
// A level switch on a tank (`tank:`): BOOL `value`, true while the level is `above` (or `below`)
// a threshold, given in % of the capacity or as a height (mm). With `hysteresis` (same kind),
// an `above` switch turns on at the threshold and off only below threshold − hysteresis (a
// `below` switch: on at the threshold, off above threshold + hysteresis), so a level lapping at
// the threshold does not chatter. FaultPlan::stuckOutput 0/1 freezes the output.
#include <memory>
#include <string>

#include "plant/device.hpp"

namespace virtcom::plant {

class LevelSwitch final : public Device {
 public:
  struct Params {
    bool above = true;
    bool inPercent = true;      // threshold and hysteresis as a ratio of the capacity, else in m
    double threshold = 0, hysteresis = 0;
  };
  LevelSwitch(std::string name, uint32_t vessel, Params params);
  void step(const StepContext& ctx) override;
  bool value() const { return value_; }

 private:
  uint32_t vessel_ = 0;
  Params p_;
  size_t valuePort_ = 0;
  bool value_ = false;
};

std::unique_ptr<Device> makeLevelSwitch(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
