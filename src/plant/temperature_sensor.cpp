#include "plant/temperature_sensor.hpp"

#include <cmath>

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

TemperatureSensor::TemperatureSensor(std::string name, uint32_t vessel, bool asInt, int64_t lagNs)
    : Device(std::move(name), "temperature_sensor"), vessel_(vessel), asInt_(asInt), lagNs_(lagNs) {
  valuePort_ = asInt ? addPort("value", ElemType::Int, PortDir::Out, "tank temperature in 0.1 °C")
                     : addPort("value", ElemType::Real, PortDir::Out, "tank temperature in °C");
}

void TemperatureSensor::step(const StepContext& ctx) {
  const double actualC = ctx.world.vesselAt(vessel_).temperatureC;
  if (!started_ || lagNs_ <= 0) {
    readingC_ = actualC;  // the initial reading is the tank's: the sensor has been in it for ever
  } else {
    const double dt = static_cast<double>(ctx.nowNs - lastNs_);
    readingC_ += (actualC - readingC_) * (1 - std::exp(-dt / static_cast<double>(lagNs_)));
  }
  started_ = true;
  lastNs_ = ctx.nowNs;
  if (asInt_) ctx.bus.setInt(tag(valuePort_), std::llround(readingC_ * 10));
  else ctx.bus.setReal(tag(valuePort_), readingC_);
}

std::unique_ptr<Device> makeTemperatureSensor(const std::string& name, ConfigReader& cfg, World& world) {
  const int32_t vessel = vesselRef(cfg, "tank", world, true);
  const std::string output = cfg.optString("output", "real");
  if (output != "real" && output != "int")
    cfg.error(cfg.node().find("output")->loc(), "'output' must be real (°C) or int (0.1 °C), found '" + output + "'");
  const int64_t lagNs = optDurationNs(cfg, "lag", 0);
  return std::make_unique<TemperatureSensor>(name, static_cast<uint32_t>(vessel < 0 ? 0 : vessel), output == "int", lagNs);
}

}  // namespace virtcom::plant
