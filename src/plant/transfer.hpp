#pragma once
// The liquid a valve or pump moves: from a tank (`from:`), into a tank (`to:`) or between two,
// at `flow` when fully open / running. Without `from` the source is a supply line at
// `inlet_temperature`; without `to` the liquid leaves the cell (a drain). Nothing flows out of an
// empty tank.
#include <cstdint>

#include "core/config_node.hpp"
#include "plant/world.hpp"

namespace virtcom::plant {

struct Transfer {
  int32_t from = -1, to = -1;  // vessel ids, -1: outside the cell
  size_t fromFeed = 0, toFeed = 0;
  double flowM3s = 0;
  double inletC = 20;

  // This tick's feeds at `fraction` (0..1) of the full flow. Allocation-free.
  void apply(World& world, int64_t nowNs, double fraction) const;
};

// Reads `from`, `to` (at least one), `flow` and `inlet_temperature`; reports through cfg.
Transfer readTransfer(ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
