#pragma once
// Siemens positioning axis (S110/S120 EPos basic positioner) on Standard Telegram 111
// (docs/drives.md; behaviour: docs/universal-axis.md, EPos): the PROFIdrive state machine, every
// EPos mode (MDI relative/absolute positioning, MDI setup, reference point approach, set reference
// point, flying referencing, traversing blocks, jog, incremental jog), the stepped position profile
// with velocity/acceleration/deceleration overrides, a first-order position loop with
// following-error, positioning-window and standstill monitoring (F07452/F07451/F07450), software
// limit switches, master/slave sign-of-life (F01912) and setpoint-timeout monitoring. Positions are
// in LU; parameters keep their SINAMICS numbers and are simulator defaults [S] set in the cell file
// (docs/universal-axis.md, EPos positioning axis).
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "drives/drive_messages.hpp"
#include "drives/position_profile.hpp"
#include "drives/profidrive_state.hpp"
#include "drives/telegram_device.hpp"

namespace virtcom::drives {

// One traversing block (p2616..p2623): docs/universal-axis.md, EPos modes.
struct TraversingBlock {
  enum class Task : uint8_t { PositionAbs, PositionRel, EndlessPos, EndlessNeg, Wait, Goto, SetOutput, ResetOutput };
  enum class Advance : uint8_t { End, ContinueWithStop, ContinueFlying, ContinueExternal };
  uint8_t number = 0;
  Task task = Task::PositionAbs;
  Advance advance = Advance::End;
  int32_t position = 0;       // LU (p2617)
  int32_t velocity = 100;     // 1000 LU/min (p2618)
  double accelPercent = 100;  // p2619
  double decelPercent = 100;  // p2620
  int32_t parameter = 0;      // p2622: WAIT ms, GOTO block number, SET_O/RESET_O output 1..3
};

struct EposParams {
  double p2000 = 1350;       // reference speed, rpm (NIST_B: 0x40000000 = 100 %)
  double p2506 = 10000;      // LU per load revolution
  double p2571 = 30000;      // maximum velocity, 1000 LU/min
  double p2572 = 100;        // maximum acceleration, 1000 LU/s^2
  double p2573 = 100;        // maximum deceleration, 1000 LU/s^2
  double tauXS = 0.010;      // position loop: actual follows the setpoint with this lag
  double p2546 = 1000;       // dynamic following error tolerance, LU (F07452)
  double p2544 = 40;         // positioning window, LU
  double p2545S = 1.0;       // positioning monitoring time (F07451)
  double p2542 = 200;        // standstill window, LU (F07450)
  double p2543S = 0.2;       // standstill monitoring time
  double p2161 = 5;          // speed threshold 3, rpm (ZSW1.13 standstill)
  double p2585 = -300;       // jog 1 velocity, 1000 LU/min
  double p2586 = 300;        // jog 2 velocity, 1000 LU/min
  double p2587 = 1000;       // jog 1 incremental distance, LU
  double p2588 = 1000;       // jog 2 incremental distance, LU
  double p2599 = 0;          // reference point coordinate, LU
  double p2600 = 0;          // reference point offset (travel after the zero mark), LU
  double p2605 = 5000;       // reference cam search velocity, 1000 LU/min
  double p2606 = 0;          // maximum distance to the reference cam, LU; 0 = unlimited
  double p2608 = 300;        // zero mark approach velocity, 1000 LU/min
  double p2611 = 300;        // reference point approach velocity, 1000 LU/min
  bool hasRefCam = true;
  double refCamPos = 20000;  // machine position of the reference cam, LU
  double zeroMarkPos = 0;    // machine position of a zero mark; the others every pitch
  double zeroMarkPitch = 10000;
  std::array<double, 2> probePos{5000, 5000};  // machine positions of probe 1 and 2
  double p2580 = -1e9;       // software limit switch minus, LU
  double p2581 = 1e9;        // software limit switch plus, LU
  double startPosition = 0;  // machine position at power-up, LU
  int64_t monitoringNs = 100'000'000;  // setpoint timeout (p2044 / p8840); 0 = off
  uint16_t commFault = 1910;           // F01910 or F08501
  bool solMonitor = false;   // sign-of-life monitoring (isochronous mode)
  int p0925 = 1;             // tolerated consecutive sign-of-life errors
  bool ackMirror = false;    // ZSW1.12 mirrors STW1.6 instead of toggling per task
  std::vector<TraversingBlock> blocks;
};

class EposAxis final : public TelegramDevice {
 public:
  enum class Mode : uint8_t { None, MdiPositioning, MdiSetup, ReferenceApproach, Blocks, Jog, JogIncremental };

  EposAxis(std::string name, DriveCommon common, EposParams params);

  DriveState state() const { return state_; }
  Mode mode() const { return mode_; }
  const FaultBuffer& faultBuffer() const { return faults_; }
  const AlarmBuffer& alarmBuffer() const { return alarms_; }
  double actualPositionLu() const { return machinePos_ + offset_; }
  double followingErrorLu() const { return profile_.x() - machinePos_; }
  // An external force moves the load by `lu` (a collision, a hand on the axis).
  void disturb(double lu) { machinePos_ += lu; }
  void raiseFault(uint16_t number, Reaction reaction, int64_t nowNs);

 protected:
  void integrate(double dtS) override;
  void onFrame(std::span<const uint32_t> rx, int64_t nowNs) override;
  void onMissingFrame(int64_t nowNs) override;
  void encode(RawWords& tx) const override;
  void raiseInjected(Injection& inj, int64_t nowNs) override;
  void clearInjected(Injection& inj, int64_t nowNs) override;
  bool settled() const override;

 private:
  // epos_axis.cpp: frames, state machine, monitoring, status words
  void updateState();
  void checkSignOfLife(uint32_t stw2, int64_t nowNs);
  void monitor(double dtS);
  bool standstill() const;
  // epos_modes.cpp: mode selection on a frame, motion every step
  void selectMode(uint32_t previous, uint32_t previousPos2, int64_t nowNs);
  void startMdi(int64_t nowNs);
  void startBlock(uint8_t number, int64_t nowNs);
  void beginBlock(size_t index, int depth);
  void blockDone(int depth);
  void blockStep(const ProfileLimits& lim, double dtS);
  void startReferencing();
  void startJog(bool jog2, bool incremental);
  void endTask();
  void acceptTask();
  void setReference(double machinePos);
  void checkFlyingProbe(double before, double after);
  void motion(double dtS);
  void referencingStep(double dtS);
  void updateLimitFlags();
  ProfileLimits limits(double velocity1000LuMin, double accelPercent, double decelPercent) const;
  const ProfileLimits& taskLimits();
  double clampToSoftwareLimits(double machineTarget) const;
  void moveAtVelocity(double v, const ProfileLimits& lim, double dtS);
  bool taskActive() const { return mode_ != Mode::None; }

  EposParams p_;
  double alphaX_ = 0;
  DriveState state_ = DriveState::S1SwitchingOnInhibited;
  // last accepted command words
  uint32_t stw1_ = 0x0006, posStw1_ = 0, posStw2_ = 0, stw2_ = 0;
  uint32_t override_ = 0x4000, mdiAcc_ = 0x4000, mdiDec_ = 0x4000;
  int32_t mdiTarget_ = 0, mdiVelocity_ = 0;
  bool accepted_ = false;
  // motion
  PositionProfile profile_;   // machine coordinates
  double machinePos_ = 0;     // actual load position, machine coordinates (LU)
  double actualLoadRpm_ = 0;  // actual load speed, rpm (kept: every use needs rpm, dividing once)
  double offset_ = 0;         // reported position = machine + offset
  double prevSetVelocity_ = 0, setAccel_ = 0;
  bool referenced_ = false;
  Mode mode_ = Mode::None;
  double target_ = 0;         // machine coordinates
  double taskVelocity_ = 0;   // 1000 LU/min
  double taskAcc_ = 100, taskDec_ = 100;  // percent
  // taskLimits() of the last step: the limits change only with a new task or OVERRIDE, so the
  // divisions are not repeated every step. NaN: nothing computed yet.
  struct LimitsMemo {
    double velocity = NAN, acc = NAN, dec = NAN;
    uint32_t override = 0;
    ProfileLimits lim;
  } taskLimits_;
  int direction_ = 0;         // setup / jog / endless: -1, 0, +1
  bool stopping_ = false;     // the task is being cancelled: brake to standstill, then end
  bool setpointStatic_ = true;
  int refPhase_ = 0;          // reference approach: 1 cam search, 2 zero mark, 3 offset
  int refDir_ = 1;
  double refStart_ = 0;
  bool refLatched_ = false;   // referencing done/failed: STW1.11 must drop before the next one
  bool flyingArmed_ = false;
  bool jogBit2_ = false;
  bool jogLatched_ = false;   // incremental jog: one move per 0 -> 1 of the jog bit
  uint8_t block_ = 0;         // active traversing block
  size_t blockIndex_ = 0;
  int64_t waitUntilNs_ = -1;
  int64_t nowNs_ = 0;
  bool externalChange_ = false;
  bool output1_ = false, output2_ = false;
  bool swLimitMinus_ = false, swLimitPlus_ = false;
  bool taskAck_ = false;
  // monitoring
  double staticS_ = 0;        // time since the setpoint became static
  bool windowReached_ = false;
  bool followingOk_ = true;
  int64_t lastFrameNs_ = 0;
  bool commFault_ = false, commAlarm_ = false;
  uint8_t masterPrev_ = 0, slaveSol_ = 0;
  int solErrors_ = 0;
  bool solStarted_ = false, solFault_ = false;
  FaultBuffer faults_;
  AlarmBuffer alarms_;
};

std::unique_ptr<plant::Device> makeEposAxis(const std::string& name, ConfigReader& cfg, plant::World& world);

}  // namespace virtcom::drives
