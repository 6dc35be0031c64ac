// The one table of device types: cell-file type name, one-line description, factory.
// createDevice() also handles the keys common to every device (`group`), marks the loader's own
// keys (`type`, `name`) as known, and rejects unknown keys once the factory has read its own.
#include <memory>

#include "plant/axis.hpp"
#include "plant/config_helpers.hpp"
#include "plant/conveyor.hpp"
#include "plant/device.hpp"
#include "plant/heater.hpp"
#include "plant/level_switch.hpp"
#include "plant/press.hpp"
#include "plant/pump.hpp"
#include "plant/robot.hpp"
#include "plant/sensor.hpp"
#include "plant/tank.hpp"
#include "plant/temperature_sensor.hpp"
#include "plant/timed_device.hpp"
#include "plant/valve.hpp"

namespace virtcom::plant {
namespace {

constexpr DeviceType kDeviceTypes[] = {
    {"robot", "industrial robot running numbered procedures (moves, tools, grip, screw) with the execute/done handshake",
     makeRobot},
    {"axis", "linear positioning axis: moves to targetPosition (mm) with a trapezoidal profile, done when in position",
     makeAxis},
    {"press", "servo press running numbered programs (approach, press, hold, return) on a locked insert", makePress},
    {"timed", "generic device whose numbered commands take a fixed time and set/clear world facts", makeTimed},
    {"conveyor", "belt conveyor moving parts at a constant speed, with position sensors", makeConveyor},
    {"sensor", "digital sensor mirroring a world fact, with an optional delay", makeSensor},
    {"tank", "well-mixed liquid tank: volume, level and temperature from its valves, pumps and heaters", makeTank},
    {"valve", "on/off process valve filling or draining a tank, with travel time and end-position feedback", makeValve},
    {"pump", "pump moving liquid into, out of or between tanks while it runs", makePump},
    {"heater", "immersion heater putting its power into a tank's liquid while on", makeHeater},
    {"level_switch", "BOOL switch on a tank's level above or below a threshold, with hysteresis", makeLevelSwitch},
    {"temperature_sensor", "a tank's liquid temperature as REAL (degC) or INT (0.1 degC), with an optional lag",
     makeTemperatureSensor},
};

}  // namespace

std::unique_ptr<Device> createDevice(const std::string& type, const std::string& name, ConfigReader& cfg, World& world,
                                     std::span<const DeviceType> extra) {
  cfg.child("type");
  cfg.child("name");
  std::vector<DeviceType> all(std::begin(kDeviceTypes), std::end(kDeviceTypes));
  all.insert(all.end(), extra.begin(), extra.end());
  for (const auto& t : all) {
    if (type != t.name) continue;
    std::unique_ptr<Device> device = t.factory(name, cfg, world);
    device->setGroup(cfg.optString("group", ""));
    cfg.rejectUnknownKeys();
    return device;
  }
  std::vector<std::string> names;
  for (const auto& t : all) names.push_back(t.name);
  const ConfigNode* typeNode = cfg.node().find("type");
  cfg.error(typeNode ? typeNode->loc() : cfg.node().loc(),
            "unknown device type '" + type + "' (expected one of: " + joinNames(names) + ")");
  return nullptr;
}

std::vector<std::pair<std::string, std::string>> deviceTypes() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& t : kDeviceTypes) out.emplace_back(t.name, t.doc);
  return out;
}

}  // namespace virtcom::plant
