#pragma once
// The part every drive simulator shares: a cell device whose ports are the words of its
// telegram (telegrams.def: words to the drive are inputs, words from the drive outputs, typed
// WORD/INT/DINT/REAL), so a PLC STRUCT with the telegram's member names or a WORD array wires
// to it; the shaft and its mechanical load (speed, position of a linear axis or belt); injected
// faults/alarms at a time or speed condition; injected communication loss; the trace activity.
//
// Every bus cycle (= device step) runs exchange(): dynamics are integrated up to now in fixed
// steps of `step` (default 1 ms) under the previous command, injections due are applied, then
// the received frame (or its absence) is processed and the reply words are encoded.
// Nothing on this path allocates or looks up a name.
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "drives/drive_messages.hpp"
#include "drives/mapped_ports.hpp"
#include "drives/telegram.hpp"
#include "plant/device.hpp"

namespace virtcom::drives {

// A fault or alarm raised by the scenario (the cell file's `faults: inject:`).
struct Injection {
  MessageKind kind = MessageKind::Fault;
  uint16_t number = 0;        // SINAMICS F/A number or PowerFlex fault number
  Reaction reaction = Reaction::None;
  int64_t atNs = 0;           // not before this time
  double minSpeedRpm = 0;     // ... and not before |shaft speed| >= this (0 = no condition)
  int64_t durationNs = 0;     // how long the cause persists; < 0 = for the rest of the run
  // run state
  bool raised = false, causeGone = false;
  int64_t raisedNs = 0;
};

struct CommLossWindow {
  int64_t fromNs = 0, toNs = 0;  // no frames are delivered in [fromNs, toNs)
};

inline constexpr double kRadPerRpm = 2.0 * std::numbers::pi / 60.0;  // rad/s per rpm

// The shaft's mechanical load: the motor turns a gearbox and a lead screw / belt pulley.
struct ShaftLoad {
  double gearRatio = 1.0;        // motor revolutions per load revolution
  double mmPerRev = 0.0;         // load travel per load revolution; 0 = position in revolutions
  double inertiaKgm2 = 0.01;     // at the motor shaft
  double loadTorqueNm = 0.0;     // constant (friction-like, against the motion)
};

struct DriveCommon {
  TelegramId telegram = TelegramId::Std1;
  int64_t stepNs = 1'000'000;    // integration step of the dynamics
  ShaftLoad load;
  std::vector<Injection> injections;
  std::vector<CommLossWindow> commLoss;
  // `mapping:` set: the ports are UNIVERSAL_AXIS signals instead of telegram words (mapped_ports.hpp).
  std::shared_ptr<const MappingSpec> mapping;
};

class TelegramDevice : public plant::Device {
 public:
  // `family`: whose fault and alarm codes the cell file may inject into this drive.
  TelegramDevice(std::string name, std::string type, DriveCommon common, MessageFamily family);

  void prepare(plant::World& world, Trace& trace) override;
  void step(const plant::StepContext& ctx) final;
  int64_t nextEventNs() const override;
  void finish(int64_t endNs, Trace& trace) override;

  // One bus cycle at nowNs with the received raw words, or without a frame (`rx` empty: the
  // controller stopped sending). Used by step() and directly by tests and benchmarks.
  void exchange(std::span<const uint32_t> rx, int64_t nowNs);
  // The words sent back to the controller after the last exchange().
  const RawWords& tx() const { return tx_; }
  TelegramId telegramId() const { return common_.telegram; }
  double shaftSpeedRpm() const { return speedRpm_; }
  // Load position: mm when the load has a lead (mm per revolution), else load revolutions.
  double loadPosition() const { return loadPosition_; }
  // The cell file's `faults:` keys of a drive (`inject`, `comm_loss`); reports through `f`.
  void readFaults(ConfigReader& f) override;

 protected:
  // Integrate the dynamics over dtS seconds; returns the motor speed (rpm) and torque (N*m) at
  // the end of the step through speedRpm_/torqueNm_.
  virtual void integrate(double dtS) = 0;
  virtual void onFrame(std::span<const uint32_t> rx, int64_t nowNs) = 0;
  virtual void onMissingFrame(int64_t nowNs) = 0;
  virtual void encode(RawWords& tx) const = 0;
  virtual void raiseInjected(Injection& inj, int64_t nowNs) = 0;
  virtual void clearInjected(Injection& inj, int64_t nowNs) = 0;
  // True while the model changes on its own (motion, ramps, pending timers).
  virtual bool settled() const = 0;

  // Torque the load needs at the motor for an acceleration (rad/s^2) at speed n (rpm). Inline:
  // every drive calls it every integration step.
  double loadTorqueNm(double speedRpm, double accelRadS2) const {
    const double friction = std::abs(speedRpm) > 0.5 ? std::copysign(common_.load.loadTorqueNm, speedRpm) : 0.0;
    return friction + common_.load.inertiaKgm2 * accelRadS2;
  }
  // One integration step of the shaft coasting with the power off: the drive's run-down time
  // constant (`coastFactor` = exp(-dt / tau_coast), the losses the model does not name) and the
  // load's friction torque, which brakes it at torque / inertia and never turns it back. Without
  // the torque a loaded shaft coasted as long as an idle one (issue 16). Inline: per step.
  double coastRpm(double speedRpm, double coastFactor, double dtS) const {
    const double v = speedRpm * coastFactor;
    const double brakeRpm = common_.load.inertiaKgm2 > 0 ? common_.load.loadTorqueNm / common_.load.inertiaKgm2 * dtS / kRadPerRpm : 0.0;
    if (std::abs(v) <= brakeRpm || std::abs(v) < 1e-3) return 0.0;
    return v - std::copysign(brakeRpm, v);
  }
  // Records a fault for the report (rare event, allocates).
  void noteFault(int64_t nowNs, const std::string& message);

  DriveCommon common_;
  double speedRpm_ = 0;
  double torqueNm_ = 0;

 private:
  void advanceTo(int64_t nowNs);
  void applyInjections(int64_t nowNs);
  bool commLost(int64_t nowNs) const;

  MessageFamily family_;  // the injection codes readFaults() accepts
  double stepS_ = 0, travelPerRpmStep_ = 0, joulesPerNmRpmStep_ = 0;  // per integration step
  RawWords rx_{}, tx_{};
  std::optional<MappedPorts> mapped_;
  size_t rxCount_ = 0, txCount_ = 0;
  size_t speedPort_ = 0, positionPort_ = 0, torquePort_ = 0;
  int64_t lastNs_ = 0;
  double loadPosition_ = 0;
  Trace* trace_ = nullptr;
  uint32_t runLabel_ = 0;
  uint32_t activity_ = 0;
  bool running_ = false;
  int64_t runStartNs_ = 0;
  int64_t busyNs_ = 0;
  double energyJ_ = 0, activityEnergyJ_ = 0;
};

}  // namespace virtcom::drives
