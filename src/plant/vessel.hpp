#pragma once
// A vessel: the contents of a tank device (volume, temperature) shared with the devices that act
// on it (valves, pumps, heaters: feeds) and that sense it (level switches, temperature sensors).
// Devices name the tank in their entry (`to: Reactor`); World interns the names at load and the
// cell loader reports a name no tank defines. Per tick everything goes by index, nothing
// allocates.
#include <cstdint>
#include <string>
#include <vector>

#include "core/source.hpp"

namespace virtcom::plant {

// What one device puts into a vessel while it holds: a volume flow (m³/s, positive into the
// vessel, negative out of it) at an inlet temperature, and heat (W).
struct Feed {
  double flowM3s = 0;
  double inletC = 20;
  double heatW = 0;
};

// One device's feed, set every tick by that device. The tank integrates over the tick ending at
// its step's time with the feed that held during that tick, whichever of the two steps first:
// a feed set in this tick only counts from this tick on.
class FeedSlot {
 public:
  void set(int64_t nowNs, const Feed& feed) {
    if (nowNs != sinceNs_) {
      before_ = current_;
      sinceNs_ = nowNs;
    }
    current_ = feed;
  }
  // The feed in force during the tick that ends at nowNs.
  const Feed& heldUntil(int64_t nowNs) const { return sinceNs_ == nowNs ? before_ : current_; }

 private:
  Feed current_, before_;
  int64_t sinceNs_ = -1;
};

struct Vessel {
  std::string name;
  SourceLocation firstUse;        // where a device first named it (for "no tank named ...")
  bool defined = false;           // a tank device owns it
  std::vector<FeedSlot> feeds;    // one per feeding device, added at load
  // published by the tank every tick (its parameters and its state)
  double capacityM3 = 0, heightM = 0;
  double volumeM3 = 0, temperatureC = 20;

  double levelRatio() const { return capacityM3 > 0 ? volumeM3 / capacityM3 : 0; }  // 0..1
  double levelM() const { return levelRatio() * heightM; }
};

}  // namespace virtcom::plant
