// The external PLC's link cut during the scenario's windows.
#include "scenario/link_loss.hpp"

#include <algorithm>

namespace virtcom::scenario {

LinkLossBridge::LinkLossBridge(BusBridge& link, std::vector<LinkLossWindow> windows, bool faultOnLoss)
    : link_(link), windows_(std::move(windows)), faultOnLoss_(faultOnLoss) {}

bool LinkLossBridge::cut(int64_t nowNs) const {
  return std::ranges::any_of(windows_, [nowNs](const LinkLossWindow& w) { return nowNs >= w.atNs && nowNs < w.atNs + w.durationNs; });
}

bool LinkLossBridge::pull(TagBus& bus, int64_t nowNs) {
  if (!cut(nowNs)) return link_.pull(bus, nowNs);
  if (!faultOnLoss_) return true;  // hold: the devices keep the last commands
  // Ends the run: the one allocation, as the bridge's own loss message does.
  failure_ = "the link to the external PLC was lost (scenario comm_loss, on_loss: fault)";
  return false;
}

void LinkLossBridge::push(const TagBus& bus, int64_t nowNs) {
  if (!cut(nowNs)) link_.push(bus, nowNs);
}

}  // namespace virtcom::scenario
