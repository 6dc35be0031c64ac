#pragma once
// An immersion heater in a tank (`tank:`): while `on` is true it puts `power` into the liquid
// (tank.hpp: the heating) and draws it from the supply; the energy is counted in the device
// totals. Trace: one `Heating` activity per period on, with its energy.
#include <memory>
#include <string>

#include "plant/device.hpp"
#include "plant/on_period.hpp"

namespace virtcom::plant {

class Heater final : public Device {
 public:
  Heater(std::string name, uint32_t vessel, size_t feed, double powerW);
  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) override;
  void finish(int64_t endNs, Trace& trace) override;

 private:
  uint32_t vessel_ = 0;
  size_t feed_ = 0;
  double powerW_ = 0;
  size_t onPort_ = 0;
  OnPeriods periods_;
};

std::unique_ptr<Device> makeHeater(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
