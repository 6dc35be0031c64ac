#pragma once
// Communication loss of the link to an external PLC (`plc: ads:`, `modbus:`, `opcua:`) as a scenario
// fault (docs/scenarios.md, `faults: - {link: plc, comm_loss: [...]}`): the cell's bridge
// (made by `virtcom test`, as `virtcom run` makes it) is wrapped, and during each window the
// link is cut as a real loss would cut it: with `on_loss: fault` the first tick of the window
// fails the bridge and the run ends as a PLC fault, as the bridge's own loss detection ends it;
// with `on_loss: hold` the bridge is not polled (no commands read, no status written): the
// devices keep the last commands, and after the window the bridge goes on and writes every
// status that changed meanwhile, as after a reconnect. Nothing is allocated per tick.
#include <cstdint>
#include <string>
#include <vector>

#include "core/bus_bridge.hpp"

namespace virtcom::scenario {

struct LinkLossWindow {
  int64_t atNs = 0;
  int64_t durationNs = 0;
};

class LinkLossBridge final : public BusBridge {
 public:
  // `link` must outlive this bridge. `faultOnLoss`: the cell's `on_loss: fault`.
  LinkLossBridge(BusBridge& link, std::vector<LinkLossWindow> windows, bool faultOnLoss);

  bool pull(TagBus& bus, int64_t nowNs) override;
  void push(const TagBus& bus, int64_t nowNs) override;
  std::string failure() const override { return failure_.empty() ? link_.failure() : failure_; }
  void simulationStopped() override { link_.simulationStopped(); }

 private:
  bool cut(int64_t nowNs) const;

  BusBridge& link_;
  std::vector<LinkLossWindow> windows_;
  bool faultOnLoss_ = true;
  std::string failure_;  // set when a window ends the run
};

}  // namespace virtcom::scenario
