#pragma once
// A digital sensor: BOOL output `value` mirroring a world fact (e.g. a part-present switch on
// `bearing1Placed`). With `delay`, the output follows the fact only once the fact has held its
// new value for that long (on- and off-delay alike, so glitches shorter than the delay never
// show). `invert: true` reports the negated fact. FaultPlan::stuckOutput 0/1 freezes the output.
#include <memory>
#include <string>

#include "plant/device.hpp"

namespace virtcom::plant {

class Sensor final : public Device {
 public:
  Sensor(std::string name, uint32_t fact, int64_t delayNs, bool invert);
  void step(const StepContext& ctx) override;
  int64_t nextEventNs() const override;
  bool value() const { return value_; }
  // `delay` and `invert` change mid-run (a change of the fact already pending is judged by the
  // new delay; a new `invert` shows after the delay, as a change of the fact would); the fact
  // it senses does not.
  bool changesParameter(std::string_view key) const override { return key == "delay" || key == "invert"; }
  void swapParameters(Device& edited) override;

 private:
  size_t valuePort_ = 0;
  uint32_t fact_ = 0;
  int64_t delayNs_ = 0;
  bool invert_ = false;
  bool started_ = false;
  bool value_ = false;    // debounced output (before stuckOutput)
  bool pending_ = false;  // the fact differs from value_ since pendingSinceNs_
  int64_t pendingSinceNs_ = 0;
};

std::unique_ptr<Device> makeSensor(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
