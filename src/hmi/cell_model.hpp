#pragma once
// The static half of the HMI: what does not change while the cell runs (devices with their
// ports, kind-specific geometry and place on the layout, zones, activity labels, signals, the
// PLC's base tick), as the JSON of GET /api/model (docs/hmi.md). Built once at start-up.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "cell/cell.hpp"

namespace virtcom::hmi {

// Precondition: the devices are prepared (labels interned: after sim::Simulation's constructor).
nlohmann::json cellModel(const cell::Cell& cell, int64_t baseTickNs);

}  // namespace virtcom::hmi
