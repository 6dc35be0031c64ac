#pragma once
// A tank of `capacity` (and `height`, for levels in mm) holding one well-mixed liquid: its volume
// is the sum of the feeds of the valves and pumps wired to it (their `to:`/`from:` name it), its
// temperature follows the heat of its heaters, the temperature of what flows in and the loss to
// the ambient. Per tick, over the tick that just ended (explicit Euler, order: inflow mixed in,
// outflow taken, then heat):
//   V += Σ inflow·dt;  T = (V₀·T₀ + Σ inflow·dt·T_in) / V       (well mixed)
//   V -= min(Σ outflow·dt, V)                                    (an empty tank gives nothing)
//   T += Σ P·dt / (ρ·V·c), then T = T_amb + (T − T_amb)·exp(−k·dt / (ρ·V·c))
//                                  (only with liquid in it; the loss decays exactly, so stably)
// V is clamped to the capacity; `overflow` is true while it spills. Outputs are REALs: volume
// (l), level (% of capacity), level_mm, temperature (°C).
#include <memory>
#include <string>

#include "plant/device.hpp"

namespace virtcom::plant {

class Tank final : public Device {
 public:
  struct Params {
    double capacityM3 = 1, heightM = 1;
    double initialRatio = 0, initialC = 20, ambientC = 20;
    double heatLossWPerK = 0, densityKgM3 = 1000, specificHeatJPerKgK = 4186;
  };
  Tank(std::string name, uint32_t vessel, Params params);
  void step(const StepContext& ctx) override;

 private:
  void integrate(Vessel& v, int64_t nowNs, double dtS);
  Params p_;
  uint32_t vessel_ = 0;
  size_t volumePort_ = 0, levelPort_ = 0, levelMmPort_ = 0, temperaturePort_ = 0, overflowPort_ = 0;
  bool started_ = false, overflow_ = false;
  int64_t lastNs_ = 0;
};

std::unique_ptr<Device> makeTank(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
