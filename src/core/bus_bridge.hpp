#pragma once
// A link between the tag bus and a peer outside the simulation (a Modbus or ADS client or
// server). The simulation calls both hooks every base tick on its own thread:
//   ... PLC scan, PLC variables -> device inputs, pull(), devices step, push(), recording ...
// so what a peer wrote reaches the devices in the same tick, and it sees the devices' state
// after they stepped. Implementations allocate nothing and look nothing up by name per tick.
#include <cstdint>
#include <string>

#include "core/tag_bus.hpp"

namespace virtcom {

class BusBridge {
 public:
  virtual ~BusBridge() = default;
  // The peer's values into the tags it drives (device commands). False: the link has failed
  // in a way that must end the run; failure() says why.
  virtual bool pull(TagBus& bus, int64_t nowNs) = 0;
  // The tags the peer reads (device status) out to it.
  virtual void push(const TagBus& bus, int64_t nowNs) = 0;
  // Why pull() returned false (one line).
  virtual std::string failure() const { return {}; }
  // The run has ended (called once, on the simulation's thread): a client bridge may release
  // what it holds at the peer and disconnect.
  virtual void simulationStopped() {}
};

}  // namespace virtcom
