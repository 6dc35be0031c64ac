#include "drives/drive_registry.hpp"

#include "drives/epos_axis.hpp"
#include "drives/powerflex.hpp"
#include "drives/speed_axis.hpp"

namespace virtcom::drives {
namespace {

constexpr plant::DeviceType kDriveTypes[] = {
    {"g120", "Siemens speed axis (G120-like) on PROFIdrive Standard Telegram 1 or Telegram 352", makeSpeedAxis},
    {"powerflex525", "Rockwell PowerFlex 525 on EtherNet/IP, velocity logic command/status and 0.01 Hz reference",
     makePowerFlex525},
    {"powerflex750", "Rockwell PowerFlex 750 on EtherNet/IP, 32-bit logic command/status and REAL reference",
     makePowerFlex750},
    {"s120_epos", "Siemens positioning axis (S120 EPos basic positioner) on PROFIdrive Standard Telegram 111", makeEposAxis},
};

}  // namespace

std::span<const plant::DeviceType> deviceTypes() { return kDriveTypes; }

}  // namespace virtcom::drives
