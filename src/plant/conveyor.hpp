#pragma once
// A belt conveyor of `length` moving parts at `speed` while `run` is true (towards 0 when
// `reverse` is also true). Parts are intervals [p, p + part_length] along the belt; they stop at
// the belt ends (end stoppers) and queue behind each other without overlapping. With
// `spawn_interval`, a new part is put at the start (p = 0) at the first running tick and then
// every spawn_interval of forward running time, as soon as the start is free. Every `sensors:`
// entry is a BOOL output true while a part covers its position (p <= x <= p + part_length).
// `end_fact` (optional) is set while a part rests at the downstream end; when another device
// clears it (a robot's `grip`), that part is removed from the belt.
// Trace: one "Running" activity per period of motion; energy = power x running time.
// Deterministic: positions are integer nanometres advanced by round(speed x dt) per tick, in a
// fixed part order; spawn times inside a long tick are honoured exactly.
#include <memory>
#include <string>
#include <vector>

#include "plant/device.hpp"

namespace virtcom::plant {

class Conveyor final : public Device {
 public:
  struct SensorSpec {
    std::string name;
    int64_t positionNm = 0;
    size_t port = 0;
  };
  struct Params {
    double speed = 0;                                // m/s (= nm/ns)
    int64_t lengthNm = 0, partLengthNm = 100'000'000;
    int64_t spawnIntervalNs = 0;                     // 0 = no spawning
    double idlePowerW = 0, powerW = 0;
    int32_t endFact = -1;
    std::vector<int64_t> initialPartsNm;             // p of each part
    std::vector<SensorSpec> sensors;
  };

  Conveyor(std::string name, Params params);
  const Params& params() const { return p_; }
  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) override;
  int64_t nextEventNs() const override;
  void finish(int64_t endNs, Trace& trace) override;

  size_t partCount() const { return parts_.size(); }
  // The `run` port and the label of its activities, for recording them from outside
  // (sim/operation_recogniser.hpp). The label after prepare().
  size_t runPort() const { return runPort_; }
  uint32_t runningLabel() const { return runLabel_; }
  double partPositionM(size_t i) const { return static_cast<double>(parts_[i]) * 1e-9; }

 private:
  void advance(int64_t dtNs);
  void move(int64_t dsNm);
  void spawn(int64_t dtNs);
  bool atEnd() const;
  Params p_;
  size_t runPort_ = 0, reversePort_ = 0, movingPort_ = 0;
  std::vector<int64_t> parts_;  // p of each part in nm, ascending; capacity reserved at load
  bool started_ = false;
  bool moving_ = false;
  bool reverse_ = false;
  bool endPublished_ = false;
  int64_t lastNs_ = 0;
  int64_t spawnTimerNs_ = 0;
  uint32_t runLabel_ = 0;
  uint32_t activity_ = 0;
  int64_t runStartNs_ = 0;
  int64_t busyNs_ = 0;
};

std::unique_ptr<Device> makeConveyor(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
