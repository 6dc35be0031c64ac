#pragma once
// An on/off process valve (transfer.hpp: what it connects): `open` commands it, the plug travels
// between closed and fully open in `travel_time` (linearly; 0: at once) and the flow is that
// fraction of `flow`. Feedback `opened` (fully open) and `closed` (fully closed), as the limit
// switches of a real valve. Trace: one `Open` activity per period the valve is not closed.
#include <memory>
#include <string>

#include "plant/device.hpp"
#include "plant/on_period.hpp"
#include "plant/transfer.hpp"

namespace virtcom::plant {

class Valve final : public Device {
 public:
  Valve(std::string name, Transfer transfer, int64_t travelNs);
  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) override;
  void finish(int64_t endNs, Trace& trace) override;
  double opening() const { return opening_; }

 private:
  Transfer transfer_;
  int64_t travelNs_ = 0;
  size_t openPort_ = 0, openedPort_ = 0, closedPort_ = 0;
  double opening_ = 0;  // 0 closed .. 1 fully open
  int64_t lastNs_ = 0;
  OnPeriods periods_{0};
};

std::unique_ptr<Device> makeValve(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
