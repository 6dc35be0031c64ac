#include "drives/speed_axis.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <string_view>
#include <utility>

#include "drives/normalisation.hpp"

namespace virtcom::drives {
namespace {

// Word slots and bits, resolved from the tables at compile time. Telegram 352 starts with the
// words of telegram 1, so one set of indices serves both.
constexpr uint8_t kStw1 = wordSlot(TelegramId::Std1, Dir::ToDrive, "STW1").index;
constexpr uint8_t kNsoll = wordSlot(TelegramId::Std1, Dir::ToDrive, "NSOLL_A").index;
constexpr uint8_t kZsw1 = wordSlot(TelegramId::Std1, Dir::FromDrive, "ZSW1").index;
constexpr uint8_t kNist = wordSlot(TelegramId::Std1, Dir::FromDrive, "NIST_A").index;
static_assert(wordSlot(TelegramId::Siemens352, Dir::ToDrive, "STW1").index == kStw1 &&
              wordSlot(TelegramId::Siemens352, Dir::ToDrive, "NSOLL_A").index == kNsoll &&
              wordSlot(TelegramId::Siemens352, Dir::FromDrive, "ZSW1").index == kZsw1 &&
              wordSlot(TelegramId::Siemens352, Dir::FromDrive, "NIST_A_GLATT").index == kNist);
constexpr uint8_t kCurrent = wordSlot(TelegramId::Siemens352, Dir::FromDrive, "IAIST_GLATT").index;
constexpr uint8_t kTorque = wordSlot(TelegramId::Siemens352, Dir::FromDrive, "MIST_GLATT").index;
constexpr uint8_t kWarn = wordSlot(TelegramId::Siemens352, Dir::FromDrive, "WARN_CODE").index;
constexpr uint8_t kFault = wordSlot(TelegramId::Siemens352, Dir::FromDrive, "FAULT_CODE").index;

namespace stw {
constexpr BitDef On = bitDef(Layout::Stw1Speed, "On");
constexpr BitDef NoOff2 = bitDef(Layout::Stw1Speed, "NoOff2");
constexpr BitDef NoOff3 = bitDef(Layout::Stw1Speed, "NoOff3");
constexpr BitDef EnableOperation = bitDef(Layout::Stw1Speed, "EnableOperation");
constexpr BitDef EnableRfg = bitDef(Layout::Stw1Speed, "EnableRfg");
constexpr BitDef ContinueRfg = bitDef(Layout::Stw1Speed, "ContinueRfg");
constexpr BitDef EnableSetpoint = bitDef(Layout::Stw1Speed, "EnableSetpoint");
constexpr BitDef AckFault = bitDef(Layout::Stw1Speed, "AckFault");
constexpr BitDef ControlByPlc = bitDef(Layout::Stw1Speed, "ControlByPlc");
constexpr BitDef InvertSetpoint = bitDef(Layout::Stw1Speed, "InvertSetpoint");
constexpr BitDef OpenBrake = bitDef(Layout::Stw1Speed, "OpenBrake");
constexpr BitDef MopRaise = bitDef(Layout::Stw1Speed, "MopRaise");
constexpr BitDef MopLower = bitDef(Layout::Stw1Speed, "MopLower");
}  // namespace stw

namespace zsw {
constexpr BitDef FaultActive = bitDef(Layout::Zsw1Speed, "FaultActive");
constexpr BitDef NoOff2Active = bitDef(Layout::Zsw1Speed, "NoOff2Active");
constexpr BitDef NoOff3Active = bitDef(Layout::Zsw1Speed, "NoOff3Active");
constexpr BitDef AlarmActive = bitDef(Layout::Zsw1Speed, "AlarmActive");
constexpr BitDef SpeedWithinTolerance = bitDef(Layout::Zsw1Speed, "SpeedWithinTolerance");
constexpr BitDef ControlRequested = bitDef(Layout::Zsw1Speed, "ControlRequested");
constexpr BitDef ComparisonReached = bitDef(Layout::Zsw1Speed, "ComparisonReached");
constexpr BitDef NoLimitReached = bitDef(Layout::Zsw1Speed, "NoLimitReached");
constexpr BitDef BrakeOpen = bitDef(Layout::Zsw1Speed, "BrakeOpen");
constexpr BitDef NoMotorOvertemp = bitDef(Layout::Zsw1Speed, "NoMotorOvertemp");
constexpr BitDef RotatesForward = bitDef(Layout::Zsw1Speed, "RotatesForward");
constexpr BitDef NoThermalOverload = bitDef(Layout::Zsw1Speed, "NoThermalOverload");
}  // namespace zsw

constexpr uint16_t kAlarmNotControlled = 1920;  // A01920: cyclic connection interrupted

double approach(double from, double to, double maxStep) {
  return from < to ? std::min(to, from + maxStep) : std::max(to, from - maxStep);
}

}  // namespace

SpeedAxis::SpeedAxis(std::string name, DriveCommon common, SpeedAxisParams params)
    : TelegramDevice(std::move(name), "g120", std::move(common), MessageFamily::Sinamics), p_(params) {
  if (p_.p1082 <= 0) p_.p1082 = p_.p2000;
  if (p_.p2141 < 0) p_.p2141 = 0.01 * p_.p2000;
  const double dtS = static_cast<double>(common_.stepNs) * 1e-9;
  alphaSpeed_ = 1.0 - std::exp(-dtS / p_.tauSpeedS);
  coastFactor_ = std::exp(-dtS / p_.tauCoastS);
  alphaGlatt_ = 1.0 - std::exp(-dtS / p_.p0045S);
  // Slopes are fractions of p1082 per ramp time (docs/drive-simulators.md, Setpoint channel).
  upStep_ = p_.p1082 / p_.p1120S * dtS;
  off1Step_ = p_.p1082 / p_.p1121S * dtS;
  off3Step_ = p_.p1082 / p_.p1135S * dtS;
  radPerS2PerRpmStep_ = kRadPerRpm / dtS;
  n2PerRpm_ = kN2Full / p_.p2000;
  // The MOP integrates at p1082/p1047 rpm/s (docs/drive-simulators.md, Setpoint channel).
  mop_.step = p_.p1082 / p_.p1047S * dtS;
  mop_.maximum = p_.p1082;
  mop_.value = mopStartRpm();
}

bool SpeedAxis::changesParameter(std::string_view key) const {
  static constexpr std::string_view kLive[] = {"p1120", "p1121", "p1135", "p1047", "tau_speed", "tau_coast", "p0045", "p1226",
                                               "p1227", "p1228", "p2163", "p2164", "p2166", "torque_limit", "monitoring_time"};
  return std::ranges::find(kLive, key) != std::end(kLive);
}

// The edited axis has the same step (`step` does not change), so its slopes and filter factors,
// derived in its constructor, are this axis's with the new parameters.
void SpeedAxis::swapParameters(plant::Device& edited) {
  auto& other = static_cast<SpeedAxis&>(edited);
  std::swap(p_, other.p_);
  std::swap(alphaSpeed_, other.alphaSpeed_);
  std::swap(coastFactor_, other.coastFactor_);
  std::swap(alphaGlatt_, other.alphaGlatt_);
  std::swap(upStep_, other.upStep_);
  std::swap(off1Step_, other.off1Step_);
  std::swap(off3Step_, other.off3Step_);
  std::swap(mop_.step, other.mop_.step);
}

double SpeedAxis::setpointRpm() const {
  if (!test(stw_, stw::EnableSetpoint)) return 0;
  // With the MOP configured its output is the main setpoint (p1070 = r1050) and NSOLL_A is unused.
  const double main = p_.mop ? mop_.value : rpmFromN2(nsoll_, p_.p2000);
  const double n = main * (test(stw_, stw::InvertSetpoint) ? -1.0 : 1.0);
  return std::clamp(n, -p_.p1082, p_.p1082);
}

void SpeedAxis::rampRfg() {
  switch (state_) {
    case DriveState::S4OperationEnabled: {
      if (!test(stw_, stw::EnableRfg)) {
        rfgOut_ = approach(rfgOut_, 0, off3Step_);
      } else if (test(stw_, stw::ContinueRfg)) {
        const double target = setpointRpm();
        const bool away = std::abs(target) > std::abs(rfgOut_) && target * rfgOut_ >= 0;
        rfgOut_ = approach(rfgOut_, target, away ? upStep_ : off1Step_);
      }
      break;
    }
    case DriveState::S5aOff1RampDown: rfgOut_ = approach(rfgOut_, 0, off1Step_); break;
    case DriveState::S5bOff3QuickStop: rfgOut_ = approach(rfgOut_, 0, off3Step_); break;
    default: rfgOut_ = 0; break;
  }
}

void SpeedAxis::integrate(double dtS) {
  if (mopActive()) mop_.tick(test(stw_, stw::MopRaise), test(stw_, stw::MopLower));
  rampRfg();
  const double before = speedRpm_;
  if (pulsesEnabled(state_)) {
    speedRpm_ += (rfgOut_ - speedRpm_) * alphaSpeed_;
  } else {
    speedRpm_ = coastRpm(speedRpm_, coastFactor_, dtS);
  }
  const double accel = (speedRpm_ - before) * radPerS2PerRpmStep_;
  torqueNm_ = pulsesEnabled(state_) ? loadTorqueNm(speedRpm_, accel) : 0.0;
  trackStandstillAndTolerance(dtS);
  updateState();
  const double torquePu = torqueNm_ / p_.p2003;
  const double currentA = pulsesEnabled(state_) ? p_.p2002 * std::sqrt(p_.noLoadCurrent * p_.noLoadCurrent + torquePu * torquePu) : 0.0;
  nistGlatt_ += (speedRpm_ * n2PerRpm_ - nistGlatt_) * alphaGlatt_;
  currentGlatt_ += (currentA - currentGlatt_) * alphaGlatt_;
  torqueGlatt_ += (torqueNm_ - torqueGlatt_) * alphaGlatt_;
}

// Timers of the standstill detection (docs/drive-simulators.md, PROFIdrive state machine;
// actual speed: p1228, setpoint: p1227 — the latter ends an
// OFF1/OFF3 ramp even when the load keeps the motor turning) and the ZSW1.8 comparison: within
// p2163, out beyond p2163 + p2164 (the hysteresis keeps the bit from chattering at the edge), and
// the time out of tolerance for the p2166 off delay.
void SpeedAxis::trackStandstillAndTolerance(double dtS) {
  standstillS_ = std::abs(speedRpm_) < p_.p1226 ? standstillS_ + dtS : 0.0;
  setpointStandstillS_ = std::abs(rfgOut_) < p_.p1226 ? setpointStandstillS_ + dtS : 0.0;
  const double deviation = std::abs(rfgOut_ - speedRpm_);
  if (withinTolerance_ ? deviation > p_.p2163 + p_.p2164 : deviation <= p_.p2163) {
    withinTolerance_ = !withinTolerance_;
    outOfToleranceS_ = 0;
  }
  if (!withinTolerance_) outOfToleranceS_ += dtS;
}

void SpeedAxis::updateState() {
  if (!accepted_) return;  // nothing commanded yet: stay in S1
  StateInputs in;
  in.cmd = {test(stw_, stw::On), test(stw_, stw::NoOff2), test(stw_, stw::NoOff3), test(stw_, stw::EnableOperation)};
  in.faultActive = faults_.active();
  in.faultReaction = faults_.reaction();
  in.standstill = standstillS_ >= p_.p1228S || setpointStandstillS_ >= p_.p1227S;
  const DriveState next = nextState(state_, in);
  if (pulsesEnabled(next) && !pulsesEnabled(state_)) rfgOut_ = speedRpm_;  // flying restart from the actual speed
  // ON: without p1030.0 (data save) the MOP setpoint starts again from p1040.
  const bool switchedOn = state_ == DriveState::S2ReadyForSwitchingOn && next != state_ && next != DriveState::S1SwitchingOnInhibited;
  if (switchedOn && !p_.p1030Store) mop_.value = mopStartRpm();
  state_ = next;
}

void SpeedAxis::onFrame(std::span<const uint32_t> rx, int64_t nowNs) {
  lastFrameNs_ = nowNs;
  if (commFault_) faults_.causeGone(p_.commFault);
  if (commAlarm_) alarms_.clear(kAlarmNotControlled, nowNs);
  commFault_ = commAlarm_ = false;
  const uint32_t received = rx[kStw1];
  if (!test(received, stw::ControlByPlc)) {  // frame not accepted: keep the previous command
    updateState();
    return;
  }
  const bool ackEdge = test(received, stw::AckFault) && !(accepted_ && test(stw_, stw::AckFault));
  accepted_ = true;
  stw_ = received;
  nsoll_ = static_cast<int16_t>(signedValue(WireType::I16, rx[kNsoll]));
  if (ackEdge) faults_.acknowledge(nowNs);
  updateState();
}

void SpeedAxis::onMissingFrame(int64_t nowNs) {
  if (p_.monitoringNs > 0 && nowNs - lastFrameNs_ >= p_.monitoringNs) {
    if (accepted_ && !commFault_) {
      commFault_ = true;
      raiseFault(p_.commFault, Reaction::Off3, nowNs);
    } else if (!accepted_ && !commAlarm_) {
      commAlarm_ = true;
      raiseAlarm(kAlarmNotControlled, nowNs);
    }
  }
  updateState();
}

void SpeedAxis::raiseFault(uint16_t number, Reaction reaction, int64_t nowNs) {
  if (faults_.raise(number, 0, reaction, nowNs)) noteFault(nowNs, messageName(MessageKind::Fault, number));
  updateState();
}

void SpeedAxis::removeFaultCause(uint16_t number) { faults_.causeGone(number); }

void SpeedAxis::raiseAlarm(uint16_t number, int64_t nowNs) {
  alarms_.raise(number, 0, nowNs);
  updateAlarmEffects();
}

void SpeedAxis::clearAlarm(uint16_t number, int64_t nowNs) {
  alarms_.clear(number, nowNs);
  updateAlarmEffects();
}

// Rare (on raise/clear), so the catalogue scan stays off the per-tick path.
void SpeedAxis::updateAlarmEffects() {
  motorTempAlarm_ = powerUnitTempAlarm_ = false;
  for (size_t i = 0; i < alarms_.activeCount(); ++i) {
    const MessageDef* m = findMessage(MessageKind::Alarm, alarms_.entry(i).number);
    if (!m) continue;
    motorTempAlarm_ |= m->effect == StatusEffect::MotorTemp;
    powerUnitTempAlarm_ |= m->effect == StatusEffect::PowerUnitTemp;
  }
}

void SpeedAxis::encode(RawWords& tx) const {
  uint32_t z = stateStatusBits(state_);
  z = withBit(z, zsw::FaultActive, faults_.active());
  z = withBit(z, zsw::NoOff2Active, test(stw_, stw::NoOff2));
  z = withBit(z, zsw::NoOff3Active, test(stw_, stw::NoOff3));
  z = withBit(z, zsw::AlarmActive, alarms_.active());
  z = withBit(z, zsw::SpeedWithinTolerance, speedWithinTolerance());
  z = withBit(z, zsw::ControlRequested, true);
  z = withBit(z, zsw::ComparisonReached, std::abs(speedRpm_) >= p_.p2141);
  z = withBit(z, zsw::NoLimitReached, std::abs(torqueNm_) < p_.torqueLimitNm);
  z = withBit(z, zsw::BrakeOpen, p_.brake && (pulsesEnabled(state_) || test(stw_, stw::OpenBrake)));
  z = withBit(z, zsw::NoMotorOvertemp, !motorTempAlarm_);
  const int16_t nist = n2FromRpm(speedRpm_, p_.p2000);
  z = withBit(z, zsw::RotatesForward, nist >= 0);
  z = withBit(z, zsw::NoThermalOverload, !powerUnitTempAlarm_);
  tx[kZsw1] = z;
  if (telegramId() == TelegramId::Std1) {
    tx[kNist] = rawFromInt(WireType::I16, nist);
    return;
  }
  tx[kNist] = rawFromInt(WireType::I16, toInt16(nistGlatt_));
  tx[kCurrent] = rawFromInt(WireType::I16, toInt16(currentGlatt_ * kN2Full / p_.p2002));
  tx[kTorque] = rawFromInt(WireType::I16, toInt16(torqueGlatt_ * kN2Full / p_.p2003));
  tx[kWarn] = alarms_.latestNumber();
  tx[kFault] = faults_.firstNumber();
}

void SpeedAxis::raiseInjected(Injection& inj, int64_t nowNs) {
  if (inj.kind == MessageKind::Fault) raiseFault(inj.number, inj.reaction, nowNs);
  else raiseAlarm(inj.number, nowNs);
}

void SpeedAxis::clearInjected(Injection& inj, int64_t nowNs) {
  if (inj.kind == MessageKind::Fault) removeFaultCause(inj.number);
  else clearAlarm(inj.number, nowNs);
}

// Only an accepted command integrates the MOP; a lost connection holds it (the fault stops the drive).
bool SpeedAxis::mopActive() const { return p_.mop && accepted_ && !commFault_; }

bool SpeedAxis::settled() const {
  if (mopActive() && mop_.moving(test(stw_, stw::MopRaise), test(stw_, stw::MopLower))) return false;
  if (!withinTolerance_) return false;  // the deviation is still to settle (and ZSW1.8 may drop)
  // The ramp-downs end on the standstill timers (p1228 / p1227), which need the ticks.
  if (state_ == DriveState::S5aOff1RampDown || state_ == DriveState::S5bOff3QuickStop) return false;
  if (!pulsesEnabled(state_)) return speedRpm_ == 0;
  return rfgOut_ == setpointRpm() && std::abs(speedRpm_ - rfgOut_) < 1e-9;
}

}  // namespace virtcom::drives
