#pragma once
// The drive device types (cell-file `type:`), in plant's DeviceType shape so the cell loader
// passes them to plant::createDevice next to the plant's own types.
#include <span>

#include "plant/device.hpp"

namespace virtcom::drives {

std::span<const plant::DeviceType> deviceTypes();

}  // namespace virtcom::drives
