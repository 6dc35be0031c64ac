#pragma once
// Cell-file keys shared by every drive type: `step` (integration step) and `load:` (the shaft's
// mechanical load). Reports through the ConfigReader (file:line:col), never throws.
#include "core/config_node.hpp"
#include "drives/telegram_device.hpp"

namespace virtcom::drives {

DriveCommon readDriveCommon(ConfigReader& cfg, TelegramId telegram);
// Warns (C012) at every reference speed of the drive's mapping that differs from its p2000: the
// PLC would read every speed scaled by the ratio of the two.
void warnOnReferenceSpeed(ConfigReader& cfg, const DriveCommon& common, double p2000);
// A time parameter in seconds that must be > 0 (ramp times, time constants).
double positiveSeconds(ConfigReader& cfg, const std::string& key, double fallbackS);
// A time parameter in seconds that may be 0 (delays where 0 means "at once").
double nonNegativeSeconds(ConfigReader& cfg, const std::string& key, double fallbackS);
// A plain-number parameter that must be > 0 (reference speed, current, ...).
double positiveNumber(ConfigReader& cfg, const std::string& key, double fallback);
// A plain-number parameter that may be 0 (hysteresis, start values).
double nonNegativeNumber(ConfigReader& cfg, const std::string& key, double fallback);

}  // namespace virtcom::drives
