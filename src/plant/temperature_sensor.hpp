#pragma once
// A temperature sensor in a tank (`tank:`): `value` is the liquid temperature, as a REAL in °C
// or (`output: int`) an INT in tenths of a degree (as analogue input cards scale it). With
// `lag` the reading follows the tank as a first-order lag of that time constant (a sensor in a
// thermowell): y += (T − y)·(1 − e^(−dt/lag)) per tick.
#include <memory>
#include <string>

#include "plant/device.hpp"

namespace virtcom::plant {

class TemperatureSensor final : public Device {
 public:
  TemperatureSensor(std::string name, uint32_t vessel, bool asInt, int64_t lagNs);
  void step(const StepContext& ctx) override;
  double reading() const { return readingC_; }

 private:
  uint32_t vessel_ = 0;
  bool asInt_ = false;
  int64_t lagNs_ = 0;
  size_t valuePort_ = 0;
  bool started_ = false;
  double readingC_ = 0;
  int64_t lastNs_ = 0;
};

std::unique_ptr<Device> makeTemperatureSensor(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
