#pragma once
// A belt conveyor of `length` moving parts at `speed` while `run` is true (towards 0 when
// `reverse` is also true). Parts are intervals [p, p + part_length] along the belt; they stop at
// the belt ends (end stoppers) and queue behind each other without overlapping. With
// `spawn_interval`, a new part is put at the start (p = 0) at the first running tick and then
// every spawn_interval of forward running time, as soon as the start is free. Every `sensors:`
// entry is a BOOL output true while a part covers its position (p <= x <= p + part_length).
// `end_fact` (optional) is set while a part rests at the downstream end; when another device
// clears it (a robot's `grip`), that part is removed from the belt.
// Parts may be of kinds (`part_kinds`: the kinds of the spawned parts, in a repeating order, e.g.
// a lot with defective parts of two materials); a sensor may `detect` only some kinds (a defect
// camera, an inductive sensor seeing metal). `pushers` push the part covering their position off
// the belt into their bin while their command is true; with `discharge` parts run off the belt
// end into the end bin instead of stopping there. Every bin counts its parts by kind (INT ports
// `<bin>_<kind>`), and `produced_<kind>` counts the spawned ones, so a run shows where each part
// went.
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
    uint32_t kindMask = 0;  // bit k: detects kind k; 0: any part
  };
  struct PusherSpec {
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
    std::vector<std::string> kinds;                  // part kinds (at most kMaxKinds); empty: one, "parts"
    std::vector<uint8_t> pattern;                    // kinds of the spawned parts, repeated
    int64_t spawnCount = 0;                          // 0 = no limit
    bool discharge = false;                          // parts leave the belt end into the end bin
    std::vector<PusherSpec> pushers;
  };
  static constexpr size_t kMaxKinds = 32;

  Conveyor(std::string name, Params params);
  const Params& params() const { return p_; }
  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) override;
  int64_t nextEventNs() const override;
  void finish(int64_t endNs, Trace& trace) override;
  // A running belt takes a new speed, spawn_interval or spawn_count. Its geometry (length,
  // part_length, sensor and pusher positions, initial parts) and part kinds shape the parts
  // already on it, and its powers are accounted over the whole run at the end: they stay as loaded.
  bool changesParameter(std::string_view key) const override;
  void swapParameters(Device& edited) override;

  size_t partCount() const { return parts_.size(); }
  // Parts in bin `bin` (pushers in order, then the end bin) of kind `kind`.
  int64_t binCount(size_t bin, size_t kind) const { return binCounts_[bin * kindCount() + kind]; }
  // The `run` port and the label of its activities, for recording them from outside
  // (sim/operation_recogniser.hpp). The label after prepare().
  size_t runPort() const { return runPort_; }
  uint32_t runningLabel() const { return runLabel_; }
  double partPositionM(size_t i) const { return static_cast<double>(parts_[i]) * 1e-9; }
  // The kind of part i (index into params().kinds; 0 with no kinds).
  uint8_t partKind(size_t i) const { return partKinds_[i]; }

 private:
  void advance(int64_t dtNs);
  void advanceTicks(int64_t dtNs, int64_t tickNs);
  void move(int64_t dsNm);
  void spawn(int64_t dtNs);
  bool atEnd() const;
  bool covers(int64_t part, int64_t positionNm) const { return part <= positionNm && positionNm <= part + p_.partLengthNm; }
  // Parts still to spawn (spawn_count not reached).
  bool lotLeft() const { return p_.spawnCount <= 0 || spawned_ < static_cast<size_t>(p_.spawnCount); }
  size_t kindCount() const { return p_.kinds.empty() ? 1 : p_.kinds.size(); }
  void drop(size_t part, size_t bin);
  void push(const TagBus& bus);
  void publishCounts(TagBus& bus) const;
  Params p_;
  size_t runPort_ = 0, reversePort_ = 0, movingPort_ = 0;
  std::vector<int64_t> parts_;  // p of each part in nm, ascending; capacity reserved at load
  std::vector<uint8_t> partKinds_;  // the kind of each part, parallel to parts_
  size_t spawned_ = 0;
  std::vector<int64_t> binCounts_;  // [bin][kind]; the bins: pushers, then the end (discharge)
  std::vector<int64_t> produced_;   // per kind
  size_t firstCountPort_ = 0, firstProducedPort_ = 0;
  bool hasProducedPorts_ = false;
  bool started_ = false;
  bool moving_ = false;
  bool reverse_ = false;
  bool endPublished_ = false;
  bool pushing_ = false;  // a pusher's command is on: parts may reach it any tick
  int64_t lastNs_ = 0;
  int64_t tickNs_ = 0;    // the simulation's base tick, from the last step
  int64_t spawnTimerNs_ = 0;
  uint32_t runLabel_ = 0;
  uint32_t activity_ = 0;
  int64_t runStartNs_ = 0;
  int64_t busyNs_ = 0;
};

std::unique_ptr<Device> makeConveyor(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
