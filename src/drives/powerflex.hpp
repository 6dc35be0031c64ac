#pragma once
// Rockwell PowerFlex 525 and 750 on EtherNet/IP (docs/drives.md; behaviour:
// docs/drive-simulators.md, powerflex525 / powerflex750): Start latching and Stop, jog, direction
// field, accel/decel time selection, reference select (comm reference or presets), ramped output
// frequency passing through 0 Hz on reversal, AtReference, ClearFaults on 0->1, a 10-entry fault
// queue (most recent first) and the comm-loss action of C143 (fault F083/F073, stop, hold last),
// the PF525 MOP (bits 7/15) and the PF750 position mode (Reference/Feedback in degrees of an
// external load encoder). Both variants share this model; only the words differ (PF525: 16-bit
// logic words and 0.01 Hz INT; PF750: 32-bit logic words and REAL).
#include <array>
#include <memory>

#include "drives/motor_pot.hpp"
#include "drives/position_profile.hpp"
#include "drives/telegram_device.hpp"

namespace virtcom::drives {

enum class CommLossAction : uint8_t { Fault, Stop, HoldLast };

struct PowerFlexParams {
  double maxHz = 60;         // P044 maximum frequency
  double minHz = 0;          // P043 minimum frequency
  double accel1S = 10, decel1S = 10;  // P041 / P042 (time from 0 to P044 and back)
  double accel2S = 10, decel2S = 10;  // A442 / A443
  double jogHz = 10;         // A431 jog frequency
  double jogRampS = 10;      // A432 jog accel/decel time
  std::array<double, 4> presetHz{0, 5, 10, 20};  // A410..A413
  int polePairs = 1;         // rpm = Hz x 60 / pole pairs
  double tauCoastS = 2.0;    // motor run-down with the output off (fault, coast stop)
  int64_t commTimeoutNs = 100'000'000;  // I/O connection timeout; 0 = off
  CommLossAction commAction = CommLossAction::Fault;  // C143
  uint16_t commFault = 83;   // F083 EtherNet/IP comm loss (or F073 net loss)
  bool referenceInRpm = false;  // PF750: Reference/Feedback in rpm instead of Hz
  bool mop = false;          // PF525: the network references (FreqSelect 000..011) come from the MOP
  double mopTimeS = 10;      // A430 MOP time: 0 -> P044 while MOPIncrement is held [S]
  bool mopSaveOnStop = true; // A428 MOP Reset Sel: 1 Save MOP Ref; 0 Zero MOP Ref (a stop sets the MOP to 0) [S]
  bool mopPreload = false;   // A429 MOP Preload: selecting the MOP (FreqSelect 000..011) loads the output frequency [S]
  bool positionMode = false; // PF750: Reference/Feedback are the external (load) encoder's degrees
};

class PowerFlex final : public TelegramDevice {
 public:
  static constexpr size_t kQueueSize = 10;
  PowerFlex(std::string name, std::string type, DriveCommon common, PowerFlexParams params);

  bool faulted() const { return activeCount_ > 0; }
  double outputHz() const { return outHz_; }
  double mopHz() const { return mop_.value; }
  double encoderDegrees() const { return profile_.x(); }
  // Fault queue, index 0 = most recent (Fault 1 Code); 0 = empty.
  const std::array<uint16_t, kQueueSize>& faultQueue() const { return queue_; }
  void raiseFault(uint16_t number, int64_t nowNs);
  void removeFaultCause(uint16_t number);

 protected:
  void integrate(double dtS) override;
  void onFrame(std::span<const uint32_t> rx, int64_t nowNs) override;
  void onMissingFrame(int64_t nowNs) override;
  void encode(RawWords& tx) const override;
  void raiseInjected(Injection& inj, int64_t nowNs) override;
  void clearInjected(Injection& inj, int64_t nowNs) override;
  bool settled() const override;

 private:
  struct Command {
    bool stop = false, start = false, run = false, jog = false, clearFaults = false, coastStop = false;
    uint32_t direction = 0, accelSelect = 0, decelSelect = 0, refSelect = 0;
    double referenceHz = 0;  // as received (PF525: magnitude; PF750 position mode: degrees)
    bool mopIncrement = false, mopDecrement = false;  // PF525 only; last, after the positional fields
  };
  Command decodeCommand(std::span<const uint32_t> rx) const;
  double targetHz() const;
  void stepPosition(double dtS);
  void coastMotor(double dtS);
  void clearFaults();
  void applyMopPreloadAndReset();

  bool pf750_ = false;
  PowerFlexParams p_;
  double coastFactor_ = 0;
  MotorPot mop_;
  bool mopSelected_ = true;    // the last accepted FreqSelect chose the network reference (the MOP)
  PositionProfile profile_;    // position mode: setpoint = actual position of the load encoder
  double degPerSPerHz_ = 0;    // load degrees per second at 1 Hz output
  bool inPosition_ = false;
  Command cmd_;
  bool prevClear_ = false;
  bool startLatched_ = false, startBlocked_ = false, jogging_ = false, coasting_ = false;
  bool forward_ = true;
  bool useTime2Accel_ = false, useTime2Decel_ = false;
  bool accelerating_ = false, decelerating_ = false;
  double outHz_ = 0;  // signed output frequency
  int64_t lastFrameNs_ = 0;
  bool commLost_ = false;
  std::array<uint16_t, kQueueSize> queue_{};
  std::array<uint16_t, 8> active_{};    // active fault numbers
  std::array<bool, 8> causeActive_{};
  size_t activeCount_ = 0;
};

std::unique_ptr<plant::Device> makePowerFlex525(const std::string& name, ConfigReader& cfg, plant::World& world);
std::unique_ptr<plant::Device> makePowerFlex750(const std::string& name, ConfigReader& cfg, plant::World& world);

}  // namespace virtcom::drives
