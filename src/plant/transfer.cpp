#include "plant/transfer.hpp"

#include "plant/config_helpers.hpp"

namespace virtcom::plant {

void Transfer::apply(World& world, int64_t nowNs, double fraction) const {
  double flow = flowM3s * fraction;
  double temperatureC = inletC;
  if (from >= 0) {
    const Vessel& source = world.vesselAt(static_cast<uint32_t>(from));
    if (source.volumeM3 <= 0) flow = 0;
    temperatureC = source.temperatureC;
    world.vesselAt(static_cast<uint32_t>(from)).feeds[fromFeed].set(nowNs, Feed{-flow, temperatureC, 0});
  }
  if (to >= 0) world.vesselAt(static_cast<uint32_t>(to)).feeds[toFeed].set(nowNs, Feed{flow, temperatureC, 0});
}

Transfer readTransfer(ConfigReader& cfg, World& world) {
  Transfer t;
  t.from = vesselRef(cfg, "from", world, false);
  t.to = vesselRef(cfg, "to", world, false);
  if (!cfg.has("from") && !cfg.has("to"))
    cfg.error(cfg.node().loc(), "needs 'from' (the tank it empties) and/or 'to' (the tank it fills)");
  if (t.from >= 0) t.fromFeed = world.addFeed(static_cast<uint32_t>(t.from));
  if (t.to >= 0) t.toFeed = world.addFeed(static_cast<uint32_t>(t.to));
  t.flowM3s = requirePositive(cfg, "flow", Dimension::VolumeFlow);
  t.inletC = cfg.optQuantity("inlet_temperature", Dimension::Temperature, 20);
  return t;
}

}  // namespace virtcom::plant
