#pragma once
// A pump (transfer.hpp: what it connects): while `run` is true it moves `flow` and draws `power`;
// `running` is its feedback. Trace: one `Running` activity per run, with its energy.
#include <memory>
#include <string>

#include "plant/device.hpp"
#include "plant/on_period.hpp"
#include "plant/transfer.hpp"

namespace virtcom::plant {

class Pump final : public Device {
 public:
  Pump(std::string name, Transfer transfer, double powerW);
  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) override;
  void finish(int64_t endNs, Trace& trace) override;

 private:
  Transfer transfer_;
  size_t runPort_ = 0, runningPort_ = 0;
  OnPeriods periods_;
};

std::unique_ptr<Device> makePump(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
