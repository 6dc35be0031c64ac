// EposAxis: frames, the PROFIdrive state machine, the position loop, monitoring (following
// error, positioning and standstill windows, sign-of-life, setpoint timeout) and the status
// words. The modes live in epos_modes.cpp.
#include "drives/epos_axis.hpp"

#include <cmath>
#include <numbers>

#include "drives/epos_words.hpp"
#include "drives/normalisation.hpp"

namespace virtcom::drives {

using namespace epos;

namespace {
constexpr uint16_t kAlarmNotControlled = 1920;  // A01920: cyclic connection interrupted
constexpr uint16_t kSignOfLifeFault = 1912;
constexpr uint16_t kStandstillFault = 7450, kPositioningFault = 7451, kFollowingFault = 7452;
}  // namespace

EposAxis::EposAxis(std::string name, DriveCommon common, EposParams params)
    : TelegramDevice(std::move(name), "s120_epos", std::move(common), MessageFamily::Sinamics), p_(std::move(params)) {
  alphaX_ = 1.0 - std::exp(-static_cast<double>(common_.stepNs) * 1e-9 / p_.tauXS);
  machinePos_ = target_ = p_.startPosition;
  profile_.reset(machinePos_);
}

bool EposAxis::standstill() const {
  return std::abs(actualLoadRpm_) < p_.p2161 && profile_.v() == 0;
}

void EposAxis::integrate(double dtS) {
  nowNs_ += common_.stepNs;
  motion(dtS);
  const double before = machinePos_;
  if (pulsesEnabled(state_)) machinePos_ += (profile_.x() - machinePos_) * alphaX_;
  else profile_.reset(machinePos_);  // pulses off: the setpoint follows the actual (follow-up)
  checkFlyingProbe(before, machinePos_);  // the probe sees the load, not the setpoint
  const double velocity = (machinePos_ - before) / dtS;
  const double loadRpm = velocity * 60.0 / p_.p2506;
  const double accel = (loadRpm - actualLoadRpm_) * common_.load.gearRatio * kRadPerRpm / dtS;
  actualLoadRpm_ = loadRpm;
  speedRpm_ = loadRpm * common_.load.gearRatio;
  torqueNm_ = pulsesEnabled(state_) ? loadTorqueNm(speedRpm_, accel) : 0.0;
  setAccel_ = std::abs(profile_.v()) - std::abs(prevSetVelocity_);
  prevSetVelocity_ = profile_.v();
  if (state_ == DriveState::S4OperationEnabled) monitor(dtS);
  updateState();
}

// Following error, positioning window (F07451), standstill window (F07450): docs/universal-axis.md,
// EPos position loop and monitoring.
void EposAxis::monitor(double dtS) {
  followingOk_ = std::abs(followingErrorLu()) <= p_.p2546;
  if (!followingOk_) raiseFault(kFollowingFault, Reaction::Off3, nowNs_);
  if (!setpointStatic_) {
    staticS_ = 0;
    windowReached_ = false;
    return;
  }
  staticS_ += dtS;
  const double deviation = std::abs(target_ - machinePos_);
  windowReached_ = windowReached_ || deviation <= p_.p2544;
  if (!windowReached_ && staticS_ >= p_.p2545S) raiseFault(kPositioningFault, Reaction::Off1, nowNs_);
  else if (windowReached_ && staticS_ >= p_.p2543S && deviation > p_.p2542) raiseFault(kStandstillFault, Reaction::Off1, nowNs_);
}

void EposAxis::updateState() {
  if (!accepted_) return;  // nothing commanded yet: stay in S1
  StateInputs in;
  in.cmd = {test(stw1_, stw1::On), test(stw1_, stw1::NoOff2), test(stw1_, stw1::NoOff3), test(stw1_, stw1::EnableOperation)};
  in.faultActive = faults_.active();
  in.faultReaction = in.faultActive ? faults_.reaction() : Reaction::None;
  in.standstill = profile_.v() == 0;
  state_ = nextState(state_, in);
  if (state_ != DriveState::S4OperationEnabled) flyingArmed_ = false;
}

void EposAxis::onFrame(std::span<const uint32_t> rx, int64_t nowNs) {
  lastFrameNs_ = nowNs;
  if (commFault_) faults_.causeGone(p_.commFault);
  if (commAlarm_) alarms_.clear(kAlarmNotControlled, nowNs);
  commFault_ = commAlarm_ = false;
  slaveSol_ = static_cast<uint8_t>(slaveSol_ % 15 + 1);
  checkSignOfLife(rx[kStw2], nowNs);
  const uint32_t received = rx[kStw1];
  if (!test(received, stw1::ControlByPlc)) {  // not accepted: values and edges frozen
    updateState();
    return;
  }
  const uint32_t previous = accepted_ ? stw1_ : 0, previousPos2 = accepted_ ? posStw2_ : 0;
  const bool ackEdge = test(received, stw1::AckFault) && !test(previous, stw1::AckFault);
  accepted_ = true;
  stw1_ = received;
  posStw1_ = rx[kPosStw1];
  posStw2_ = rx[kPosStw2];
  stw2_ = rx[kStw2];
  override_ = std::min<uint32_t>(rx[kOverride], 0x7FFF);
  mdiTarget_ = static_cast<int32_t>(rx[kTarPos]);
  mdiVelocity_ = static_cast<int32_t>(rx[kVelocity]);
  mdiAcc_ = std::min<uint32_t>(rx[kAcc], 0x4000);
  mdiDec_ = std::min<uint32_t>(rx[kDec], 0x4000);
  if (ackEdge) faults_.acknowledge(nowNs);
  updateState();
  if (test(received, stw1::ExternalBlockChange) && !test(previous, stw1::ExternalBlockChange)) externalChange_ = true;
  if (state_ == DriveState::S4OperationEnabled && !faults_.active()) selectMode(previous, previousPos2, nowNs);
}

// The master counts 1..15 (0 skipped); more than p0925 consecutive errors raise F01912.
// Monitoring starts with the first non-zero value (docs/universal-axis.md, EPos position loop
// and monitoring).
void EposAxis::checkSignOfLife(uint32_t stw2, int64_t nowNs) {
  const auto master = static_cast<uint8_t>(field(stw2, stw2::MasterSol));
  if (!p_.solMonitor) return;
  if (!solStarted_) {
    solStarted_ = master != 0;
    masterPrev_ = master;
    return;
  }
  const uint8_t expected = static_cast<uint8_t>(masterPrev_ % 15 + 1);
  solErrors_ = master == expected ? 0 : solErrors_ + 1;
  masterPrev_ = master;
  if (solErrors_ > p_.p0925 && !solFault_) {
    solFault_ = true;
    raiseFault(kSignOfLifeFault, Reaction::Off1, nowNs);
    faults_.causeGone(kSignOfLifeFault);  // an event: acknowledge clears it
  }
  if (solErrors_ == 0) solFault_ = false;
}

void EposAxis::onMissingFrame(int64_t nowNs) {
  slaveSol_ = static_cast<uint8_t>(slaveSol_ % 15 + 1);
  if (p_.monitoringNs > 0 && nowNs - lastFrameNs_ >= p_.monitoringNs) {
    if (accepted_ && !commFault_) {
      commFault_ = true;
      raiseFault(p_.commFault, Reaction::Off3, nowNs);
    } else if (!accepted_ && !commAlarm_) {
      commAlarm_ = true;
      alarms_.raise(kAlarmNotControlled, 0, nowNs);
    }
  }
  updateState();
}

void EposAxis::raiseFault(uint16_t number, Reaction reaction, int64_t nowNs) {
  if (faults_.raise(number, 0, reaction, nowNs)) noteFault(nowNs, messageName(MessageKind::Fault, number));
  if (number == kFollowingFault || number == kPositioningFault || number == kStandstillFault) faults_.causeGone(number);
  updateState();
}

void EposAxis::raiseInjected(Injection& inj, int64_t nowNs) {
  if (inj.kind == MessageKind::Fault) raiseFault(inj.number, inj.reaction, nowNs);
  else alarms_.raise(inj.number, 0, nowNs);
}

void EposAxis::clearInjected(Injection& inj, int64_t nowNs) {
  if (inj.kind == MessageKind::Fault) faults_.causeGone(inj.number);
  else alarms_.clear(inj.number, nowNs);
}

bool EposAxis::settled() const {
  if (waitUntilNs_ >= 0) return false;
  return profile_.v() == 0 && !taskActive() && std::abs(profile_.x() - machinePos_) < 1e-6;
}

void EposAxis::encode(RawWords& tx) const {
  const double actual = machinePos_ + offset_;
  const double loadRpm = actualLoadRpm_;
  const bool pulses = pulsesEnabled(state_);
  const bool still = std::abs(loadRpm) < p_.p2161;
  uint32_t z = stateStatusBits(state_);
  z = withBit(z, zsw1::Fault, faults_.active());
  z = withBit(z, zsw1::NoOff2, test(stw1_, stw1::NoOff2));
  z = withBit(z, zsw1::NoOff3, test(stw1_, stw1::NoOff3));
  z = withBit(z, zsw1::Alarm, alarms_.active());
  z = withBit(z, zsw1::NoFollowingError, followingOk_);
  z = withBit(z, zsw1::ControlRequested, true);
  z = withBit(z, zsw1::TargetReached, setpointStatic_ && std::abs(target_ - machinePos_) <= p_.p2544);
  z = withBit(z, zsw1::ReferenceSet, referenced_);
  z = withBit(z, zsw1::TaskAck, p_.ackMirror ? test(stw1_, stw1::ActivateTask) : taskAck_);
  z = withBit(z, zsw1::Standstill, still);
  z = withBit(z, zsw1::Accelerating, setAccel_ > 0);
  z = withBit(z, zsw1::Decelerating, setAccel_ < 0);
  tx[kZsw1] = z;

  uint32_t p1 = withField(0, pzsw1::Block, mode_ == Mode::Blocks ? block_ : 0);
  p1 = withBit(p1, pzsw1::Jog, mode_ == Mode::Jog || mode_ == Mode::JogIncremental);
  p1 = withBit(p1, pzsw1::RefApproach, mode_ == Mode::ReferenceApproach);
  p1 = withBit(p1, pzsw1::Flying, flyingArmed_);
  p1 = withBit(p1, pzsw1::Blocks, mode_ == Mode::Blocks);
  p1 = withBit(p1, pzsw1::Setup, mode_ == Mode::MdiSetup);
  p1 = withBit(p1, pzsw1::Mdi, mode_ == Mode::MdiPositioning);
  tx[kPosZsw1] = p1;

  uint32_t p2 = withBit(0, pzsw2::SetpointStatic, setpointStatic_);
  p2 = withBit(p2, pzsw2::Forward, profile_.v() > 0);
  p2 = withBit(p2, pzsw2::Backward, profile_.v() < 0);
  p2 = withBit(p2, pzsw2::LimitMinus, swLimitMinus_);
  p2 = withBit(p2, pzsw2::LimitPlus, swLimitPlus_);
  p2 = withBit(p2, pzsw2::Out1, output1_);
  p2 = withBit(p2, pzsw2::Out2, output2_);
  p2 = withBit(p2, pzsw2::TaskActive, taskActive() && !setpointStatic_);
  p2 = withBit(p2, pzsw2::VelocityLimiting, override_ < 0x4000 && profile_.v() != 0);
  tx[kPosZsw2] = p2;

  uint32_t z2 = withField(0, zsw2::DataSet, field(stw2_, stw2::DataSet));
  z2 = withBit(z2, zsw2::Pulses, pulses);
  z2 = withField(z2, zsw2::SlaveSol, slaveSol_);
  tx[kZsw2] = z2;

  uint32_t m = withBit(0, meldw::RampDone, setpointStatic_);
  m = withBit(m, meldw::TorqueBelow, true);
  m = withBit(m, meldw::Below2161, still);
  m = withBit(m, meldw::Below2155, still);
  m = withBit(m, meldw::NoMotorOvertemp, true);
  m = withBit(m, meldw::NoPowerUnitOvertemp, true);
  m = withBit(m, meldw::SpeedOk, followingOk_);
  m = withBit(m, meldw::Controller, pulses);
  m = withBit(m, meldw::Ready, state_ != DriveState::S1SwitchingOnInhibited && !faults_.active());
  m = withBit(m, meldw::Pulses, pulses);
  tx[kMeldw] = m;

  // XIST_A wraps as int32 (docs/universal-axis.md, EPos position loop and monitoring).
  tx[kXist] = static_cast<uint32_t>(static_cast<int64_t>(std::nearbyint(actual)));
  tx[kNistB] = rawFromInt(WireType::I32, n4FromRpm(loadRpm, p_.p2000));
  tx[kFaultCode] = faults_.firstNumber();
  tx[kWarnCode] = alarms_.latestNumber();
}

}  // namespace virtcom::drives
