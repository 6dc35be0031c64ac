#pragma once
// Siemens speed axis (G120-like) on Standard Telegram 1 or Telegram 352 (docs/drives.md; behaviour:
// docs/drive-simulators.md, g120 and shared behaviour): the PROFIdrive state machine, the
// ramp-function generator, a first-order speed response, OFF1/OFF2/OFF3, ZSW1, smoothed actual
// values, current/torque from the shaft load, fault/alarm buffers with acknowledge on the 0->1 edge
// of STW1.7, and setpoint-timeout monitoring (F01910 / F08501, A01920 when not under PLC control),
// the standstill timers p1228/p1227, the ZSW1.8 tolerance p2163 with hysteresis p2164 and off delay
// p2166, and the optional MOP (STW1.13/.14).
// Parameters keep their SINAMICS numbers; every one is a simulator default [S] set in the cell file.
#include <algorithm>
#include <memory>

#include "drives/drive_messages.hpp"
#include "drives/motor_pot.hpp"
#include "drives/profidrive_state.hpp"
#include "drives/telegram_device.hpp"

namespace virtcom::drives {

struct SpeedAxisParams {
  double p2000 = 1350;          // reference speed, rpm (0x4000 = 100 %)
  double p1082 = 0;             // maximum speed, rpm; 0 = p2000
  double p1120S = 2.0;          // ramp-up time 0 -> p1082
  double p1121S = 2.0;          // ramp-down time p1082 -> 0 (OFF1)
  double p1135S = 0.5;          // OFF3 ramp-down time
  double tauSpeedS = 0.020;     // first-order speed response of the motor
  double tauCoastS = 2.0;       // run-down time constant with the pulses off
  double p0045S = 0.004;        // smoothing of the *_GLATT actual values
  double p1226 = 20;            // standstill threshold, rpm
  double p1228S = 0.010;        // standstill delay of the actual speed
  double p1227S = 300;          // standstill delay of the setpoint (RFG output < p1226)
  double p2163 = 90;            // speed deviation tolerance, rpm (ZSW1.8 set within it)
  double p2164 = 2;             // hysteresis, rpm: ZSW1.8 drops once the deviation exceeds p2163 + p2164
  double p2166S = 0.2;          // off delay: ZSW1.8 drops only after the deviation has stayed out this long
  bool mop = false;             // STW1.13/.14 drive a motorised potentiometer that is the main setpoint
  double p1047S = 10;           // MOP ramp time 0 -> p1082 (both directions)
  double p1040 = 0;             // MOP start value, rpm: the MOP setpoint at power-up and at every ON
  bool p1030Store = false;      // p1030.0 data save: the MOP keeps its setpoint from one ON to the next
  double p2141 = -1;            // comparison speed, rpm (ZSW1.10); < 0 = 1 % of p2000
  double p2002 = 10;            // reference current, A
  double p2003 = 10;            // reference torque, N*m
  double noLoadCurrent = 0.3;   // magnetising current with the pulses on, fraction of p2002
  double torqueLimitNm = 20;    // above this ZSW1.11 (no limit reached) drops
  int64_t monitoringNs = 100'000'000;  // p2044 / p8840 setpoint timeout; 0 = off
  uint16_t commFault = 1910;    // F01910 (integrated fieldbus) or F08501 (PROFINET/COMM board)
  bool brake = false;           // a holding brake is fitted (ZSW1.12)
};

class SpeedAxis final : public TelegramDevice {
 public:
  SpeedAxis(std::string name, DriveCommon common, SpeedAxisParams params);

  DriveState state() const { return state_; }
  const FaultBuffer& faultBuffer() const { return faults_; }
  const AlarmBuffer& alarmBuffer() const { return alarms_; }
  double rfgOutputRpm() const { return rfgOut_; }
  double mopRpm() const { return mop_.value; }
  // Mid-run parameter changes (docs/scenarios.md): the ramp and MOP ramp times, the time
  // constants, the standstill and tolerance monitoring, the torque limit and the setpoint
  // monitoring time. Not the reference and maximum speeds or p2002/p2003 (the PLC's scaling),
  // the telegram, the step, the MOP configuration, the brake or the load.
  bool changesParameter(std::string_view key) const override;
  void swapParameters(plant::Device& edited) override;
  // Test entry points for the fault and alarm buffers (the cell file injects through `faults:`).
  void raiseFault(uint16_t number, Reaction reaction, int64_t nowNs);
  void removeFaultCause(uint16_t number);
  void raiseAlarm(uint16_t number, int64_t nowNs);
  void clearAlarm(uint16_t number, int64_t nowNs);

 protected:
  void integrate(double dtS) override;
  void onFrame(std::span<const uint32_t> rx, int64_t nowNs) override;
  void onMissingFrame(int64_t nowNs) override;
  void encode(RawWords& tx) const override;
  void raiseInjected(Injection& inj, int64_t nowNs) override;
  void clearInjected(Injection& inj, int64_t nowNs) override;
  bool settled() const override;

 private:
  double setpointRpm() const;
  void rampRfg();
  void updateState();
  void trackStandstillAndTolerance(double dtS);
  bool speedWithinTolerance() const { return withinTolerance_ || outOfToleranceS_ < p_.p2166S; }
  bool mopActive() const;
  double mopStartRpm() const { return std::min(p_.p1040, p_.p1082); }
  void updateAlarmEffects();

  SpeedAxisParams p_;
  // Per integration step, computed once: filter factors, ramp steps (rpm), scale factors.
  double alphaSpeed_ = 0, coastFactor_ = 0, alphaGlatt_ = 0;
  double upStep_ = 0, off1Step_ = 0, off3Step_ = 0, radPerS2PerRpmStep_ = 0, n2PerRpm_ = 0;
  DriveState state_ = DriveState::S1SwitchingOnInhibited;
  uint32_t stw_ = 0x0006;   // last accepted STW1; before the first frame: no OFF2/OFF3
  int16_t nsoll_ = 0;
  bool accepted_ = false;   // a frame with control by PLC has been accepted
  int64_t lastFrameNs_ = 0;
  bool commFault_ = false, commAlarm_ = false;
  double rfgOut_ = 0;
  double standstillS_ = 0;          // |n_act| < p1226 for this long (p1228)
  double setpointStandstillS_ = 0;  // |RFG output| < p1226 for this long (p1227)
  bool withinTolerance_ = true;     // |n_set - n_act| <= p2163, until it exceeds p2163 + p2164
  double outOfToleranceS_ = 0;      // and out of it for this long (the p2166 off delay)
  MotorPot mop_;
  double nistGlatt_ = 0, currentGlatt_ = 0, torqueGlatt_ = 0;
  bool motorTempAlarm_ = false, powerUnitTempAlarm_ = false;
  FaultBuffer faults_;
  AlarmBuffer alarms_;
};

std::unique_ptr<plant::Device> makeSpeedAxis(const std::string& name, ConfigReader& cfg, plant::World& world);

}  // namespace virtcom::drives
