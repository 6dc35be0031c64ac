#include "drives/powerflex.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "drives/normalisation.hpp"

namespace virtcom::drives {
namespace {

constexpr uint8_t k525Command = wordSlot(TelegramId::Pf525, Dir::ToDrive, "LogicCommand").index;
constexpr uint8_t k525Freq = wordSlot(TelegramId::Pf525, Dir::ToDrive, "FreqCommand").index;
constexpr uint8_t k525Status = wordSlot(TelegramId::Pf525, Dir::FromDrive, "LogicStatus").index;
constexpr uint8_t k525Output = wordSlot(TelegramId::Pf525, Dir::FromDrive, "OutputFreq").index;
constexpr uint8_t k750Command = wordSlot(TelegramId::Pf750, Dir::ToDrive, "LogicCommand").index;
constexpr uint8_t k750Reference = wordSlot(TelegramId::Pf750, Dir::ToDrive, "Reference").index;
constexpr uint8_t k750Status = wordSlot(TelegramId::Pf750, Dir::FromDrive, "LogicStatus").index;
constexpr uint8_t k750Feedback = wordSlot(TelegramId::Pf750, Dir::FromDrive, "Feedback").index;

namespace c525 {
constexpr BitDef Stop = bitDef(Layout::Pf525Command, "Stop");
constexpr BitDef Start = bitDef(Layout::Pf525Command, "Start");
constexpr BitDef Jog = bitDef(Layout::Pf525Command, "Jog");
constexpr BitDef ClearFaults = bitDef(Layout::Pf525Command, "ClearFaults");
constexpr BitDef Direction = bitDef(Layout::Pf525Command, "Direction");
constexpr BitDef AccelRate = bitDef(Layout::Pf525Command, "AccelRate");
constexpr BitDef DecelRate = bitDef(Layout::Pf525Command, "DecelRate");
constexpr BitDef FreqSelect = bitDef(Layout::Pf525Command, "FreqSelect");
constexpr BitDef MopIncrement = bitDef(Layout::Pf525Command, "MopIncrement");
constexpr BitDef MopDecrement = bitDef(Layout::Pf525Command, "MopDecrement");
}  // namespace c525
namespace s525 {
constexpr BitDef Ready = bitDef(Layout::Pf525Status, "Ready");
constexpr BitDef Active = bitDef(Layout::Pf525Status, "Active");
constexpr BitDef CommandDir = bitDef(Layout::Pf525Status, "CommandDir");
constexpr BitDef ActualDir = bitDef(Layout::Pf525Status, "ActualDir");
constexpr BitDef Accelerating = bitDef(Layout::Pf525Status, "Accelerating");
constexpr BitDef Decelerating = bitDef(Layout::Pf525Status, "Decelerating");
constexpr BitDef Faulted = bitDef(Layout::Pf525Status, "Faulted");
constexpr BitDef AtReference = bitDef(Layout::Pf525Status, "AtReference");
constexpr BitDef CommFreqCnt = bitDef(Layout::Pf525Status, "CommFreqCnt");
constexpr BitDef CommLogicCnt = bitDef(Layout::Pf525Status, "CommLogicCnt");
}  // namespace s525
namespace c750 {
constexpr BitDef NormalStop = bitDef(Layout::Pf750Command, "NormalStop");
constexpr BitDef Start = bitDef(Layout::Pf750Command, "Start");
constexpr BitDef Jog1 = bitDef(Layout::Pf750Command, "Jog1");
constexpr BitDef ClearFault = bitDef(Layout::Pf750Command, "ClearFault");
constexpr BitDef Direction = bitDef(Layout::Pf750Command, "Direction");
constexpr BitDef AccelSelect = bitDef(Layout::Pf750Command, "AccelSelect");
constexpr BitDef DecelSelect = bitDef(Layout::Pf750Command, "DecelSelect");
constexpr BitDef RefSelect = bitDef(Layout::Pf750Command, "RefSelect");
constexpr BitDef CoastStop = bitDef(Layout::Pf750Command, "CoastStop");
constexpr BitDef Run = bitDef(Layout::Pf750Command, "Run");
constexpr BitDef Jog2 = bitDef(Layout::Pf750Command, "Jog2");
}  // namespace c750
namespace s750 {
constexpr BitDef Ready = bitDef(Layout::Pf750Status, "Ready");
constexpr BitDef Active = bitDef(Layout::Pf750Status, "Active");
constexpr BitDef CommandDir = bitDef(Layout::Pf750Status, "CommandDir");
constexpr BitDef ActualDir = bitDef(Layout::Pf750Status, "ActualDir");
constexpr BitDef Accelerating = bitDef(Layout::Pf750Status, "Accelerating");
constexpr BitDef Decelerating = bitDef(Layout::Pf750Status, "Decelerating");
constexpr BitDef Faulted = bitDef(Layout::Pf750Status, "Faulted");
constexpr BitDef AtSpeed = bitDef(Layout::Pf750Status, "AtSpeed");
constexpr BitDef Running = bitDef(Layout::Pf750Status, "Running");
constexpr BitDef Jogging = bitDef(Layout::Pf750Status, "Jogging");
constexpr BitDef Stopping = bitDef(Layout::Pf750Status, "Stopping");
constexpr BitDef SpeedMode = bitDef(Layout::Pf750Status, "SpeedMode");
constexpr BitDef PositionMode = bitDef(Layout::Pf750Status, "PositionMode");
constexpr BitDef AtZeroSpeed = bitDef(Layout::Pf750Status, "AtZeroSpeed");
constexpr BitDef EnableOn = bitDef(Layout::Pf750Status, "EnableOn");
}  // namespace s750

constexpr uint32_t kForward = 0b01, kReverse = 0b10;
constexpr double kAtReferenceHz = 0.01;  // one count of 0.01 Hz [S]

double approach(double from, double to, double maxStep) {
  return from < to ? std::min(to, from + maxStep) : std::max(to, from - maxStep);
}

}  // namespace

PowerFlex::PowerFlex(std::string name, std::string type, DriveCommon common, PowerFlexParams params)
    : TelegramDevice(std::move(name), std::move(type), std::move(common), MessageFamily::PowerFlex), p_(params) {
  pf750_ = telegramId() == TelegramId::Pf750;
  const double dtS = static_cast<double>(common_.stepNs) * 1e-9;
  coastFactor_ = std::exp(-dtS / p_.tauCoastS);
  mop_.step = p_.maxHz / p_.mopTimeS * dtS;
  mop_.maximum = p_.maxHz;
  // Output Hz -> motor rpm -> load revolutions (gear) -> degrees of the encoder on the load.
  degPerSPerHz_ = 360.0 / (p_.polePairs * common_.load.gearRatio);
}

PowerFlex::Command PowerFlex::decodeCommand(std::span<const uint32_t> rx) const {
  Command c;
  if (!pf750_) {
    const uint32_t w = rx[k525Command];
    c = {test(w, c525::Stop), test(w, c525::Start), false, test(w, c525::Jog), test(w, c525::ClearFaults), false,
         field(w, c525::Direction), field(w, c525::AccelRate), field(w, c525::DecelRate), field(w, c525::FreqSelect),
         static_cast<double>(signedValue(WireType::I16, rx[k525Freq])) / 100.0};
    c.mopIncrement = test(w, c525::MopIncrement);
    c.mopDecrement = test(w, c525::MopDecrement);
    return c;
  }
  const uint32_t w = rx[k750Command];
  const double ref = realValue(rx[k750Reference]);
  c = {test(w, c750::NormalStop), test(w, c750::Start), test(w, c750::Run), test(w, c750::Jog1) || test(w, c750::Jog2),
       test(w, c750::ClearFault), test(w, c750::CoastStop), field(w, c750::Direction), field(w, c750::AccelSelect),
       field(w, c750::DecelSelect), field(w, c750::RefSelect),
       p_.referenceInRpm ? ref * p_.polePairs / 60.0 : ref};
  return c;
}

void PowerFlex::onFrame(std::span<const uint32_t> rx, int64_t nowNs) {
  lastFrameNs_ = nowNs;
  if (commLost_ && p_.commAction == CommLossAction::Fault) removeFaultCause(p_.commFault);
  commLost_ = false;
  cmd_ = decodeCommand(rx);
  if (cmd_.clearFaults && !prevClear_) clearFaults();
  prevClear_ = cmd_.clearFaults;
  if (cmd_.direction == kForward) forward_ = true;
  else if (cmd_.direction == kReverse) forward_ = false;
  if (cmd_.accelSelect == 1 || cmd_.accelSelect == 2) useTime2Accel_ = cmd_.accelSelect == 2;
  if (cmd_.decelSelect == 1 || cmd_.decelSelect == 2) useTime2Decel_ = cmd_.decelSelect == 2;
  if (!cmd_.start) startBlocked_ = false;  // a new Start is needed after a fault
  if (p_.mop) applyMopPreloadAndReset();
  if (faulted() || cmd_.stop || cmd_.coastStop) {
    startLatched_ = false;
    jogging_ = false;
    if (cmd_.coastStop) {
      coasting_ = true;
      outHz_ = 0;  // output off at once
    }
    return;
  }
  if (cmd_.start && !startBlocked_) startLatched_ = true;
  jogging_ = cmd_.jog && !startLatched_ && !cmd_.run;
  if (startLatched_ || cmd_.run || jogging_) coasting_ = false;
}

// A429 Preload: switching FreqSelect from a preset to the MOP continues from the output
// frequency; A428 Zero MOP Ref: any stop (Stop, coast stop, fault) sets the MOP to 0.
void PowerFlex::applyMopPreloadAndReset() {
  const bool selected = cmd_.refSelect < 4;
  if (p_.mopPreload && selected && !mopSelected_) mop_.value = std::min(std::abs(outHz_), p_.maxHz);
  mopSelected_ = selected;
  if (!p_.mopSaveOnStop && (faulted() || cmd_.stop || cmd_.coastStop)) mop_.value = 0;
}

void PowerFlex::onMissingFrame(int64_t nowNs) {
  if (p_.commTimeoutNs <= 0 || commLost_ || nowNs - lastFrameNs_ < p_.commTimeoutNs) return;
  commLost_ = true;
  switch (p_.commAction) {
    case CommLossAction::Fault: raiseFault(p_.commFault, nowNs); break;
    case CommLossAction::Stop: startLatched_ = jogging_ = false; break;
    case CommLossAction::HoldLast: break;
  }
}

// The reference the output ramps to (signed Hz); 0 when stopped.
double PowerFlex::targetHz() const {
  if (faulted() || coasting_) return 0;
  const double sign = forward_ ? 1.0 : -1.0;
  if (jogging_) return sign * p_.jogHz;
  if (!startLatched_ && !cmd_.run) return 0;
  // FreqSelect 000..011: the network reference (P047/P049/P051 set to EtherNet/IP [S], or to the
  // MOP with `mop: true`); 100..111: presets.
  const double network = p_.mop ? mop_.value : cmd_.referenceHz;
  const double ref = cmd_.refSelect >= 4 ? p_.presetHz[cmd_.refSelect - 4] : network;
  const double magnitude = std::clamp(std::abs(ref), p_.minHz, p_.maxHz);
  return (ref < 0 ? -sign : sign) * magnitude;
}

void PowerFlex::integrate(double dtS) {
  if (p_.mop && !commLost_) mop_.tick(cmd_.mopIncrement, cmd_.mopDecrement);  // a lost connection holds the MOP
  const double before = outHz_;
  const double target = targetHz();
  const bool away = std::abs(target) > std::abs(outHz_) && target * outHz_ >= 0;
  double rampS = away ? (useTime2Accel_ ? p_.accel2S : p_.accel1S) : (useTime2Decel_ ? p_.decel2S : p_.decel1S);
  if (jogging_) rampS = p_.jogRampS;
  const double beforeRpm = speedRpm_;
  if (faulted() || coasting_) {
    coastMotor(dtS);
    if (p_.positionMode) profile_.reset(profile_.x() + speedRpm_ / 60.0 * p_.polePairs * degPerSPerHz_ * dtS);
  } else if (p_.positionMode) {
    stepPosition(dtS);
  } else {
    outHz_ = approach(outHz_, target, p_.maxHz / rampS * dtS);
    speedRpm_ = outHz_ * 60.0 / p_.polePairs;
  }
  accelerating_ = std::abs(outHz_) > std::abs(before);
  decelerating_ = std::abs(outHz_) < std::abs(before);
  const double accel = (speedRpm_ - beforeRpm) * kRadPerRpm / dtS;
  torqueNm_ = outHz_ != 0 ? loadTorqueNm(speedRpm_, accel) : 0.0;
}

void PowerFlex::coastMotor(double dtS) {
  outHz_ = 0;  // output off, the motor coasts
  speedRpm_ = coastRpm(speedRpm_, coastFactor_, dtS);
  if (speedRpm_ == 0) coasting_ = false;
}

// Position mode [S]: a running drive moves the load to Reference (degrees) along a trapezoid with
// the speed limit P044 and the selected accel/decel times; jog moves at A431; a stop brakes to
// rest with the decel time wherever the load then is.
void PowerFlex::stepPosition(double dtS) {
  const double vMax = p_.maxHz * degPerSPerHz_;
  const double sign = forward_ ? 1.0 : -1.0;
  inPosition_ = false;
  if (jogging_) {
    profile_.toVelocity(sign * p_.jogHz * degPerSPerHz_, {vMax, vMax / p_.jogRampS, vMax / p_.jogRampS}, dtS);
  } else {
    const ProfileLimits lim{vMax, vMax / (useTime2Accel_ ? p_.accel2S : p_.accel1S),
                            vMax / (useTime2Decel_ ? p_.decel2S : p_.decel1S)};
    if (startLatched_ || cmd_.run) inPosition_ = profile_.toPosition(cmd_.referenceHz, lim, dtS);
    else profile_.toVelocity(0, lim, dtS);
  }
  outHz_ = profile_.v() / degPerSPerHz_;
  speedRpm_ = outHz_ * 60.0 / p_.polePairs;
}

void PowerFlex::encode(RawWords& tx) const {
  const bool active = outHz_ != 0 || startLatched_ || jogging_ || cmd_.run;
  const bool actualForward = outHz_ > 0 || (outHz_ == 0 && forward_);
  const bool atReference = active && (p_.positionMode ? inPosition_ : std::abs(outHz_ - targetHz()) <= kAtReferenceHz);
  const bool commReference = cmd_.refSelect < 4;
  if (!pf750_) {
    uint32_t s = 0;
    s = withBit(s, s525::Ready, !faulted());
    s = withBit(s, s525::Active, active);
    s = withBit(s, s525::CommandDir, forward_);
    s = withBit(s, s525::ActualDir, actualForward);
    s = withBit(s, s525::Accelerating, accelerating_);
    s = withBit(s, s525::Decelerating, decelerating_);
    s = withBit(s, s525::Faulted, faulted());
    s = withBit(s, s525::AtReference, atReference);
    s = withBit(s, s525::CommFreqCnt, commReference);
    s = withBit(s, s525::CommLogicCnt, true);
    tx[k525Status] = s;
    tx[k525Output] = rawFromInt(WireType::I16, toInt16(std::abs(outHz_) * 100.0));
    return;
  }
  uint32_t s = 0;
  s = withBit(s, s750::Ready, !faulted());
  s = withBit(s, s750::Active, active);
  s = withBit(s, s750::CommandDir, forward_);
  s = withBit(s, s750::ActualDir, actualForward);
  s = withBit(s, s750::Accelerating, accelerating_);
  s = withBit(s, s750::Decelerating, decelerating_);
  s = withBit(s, s750::Faulted, faulted());
  s = withBit(s, s750::AtSpeed, atReference);
  s = withBit(s, s750::Running, startLatched_ || cmd_.run);
  s = withBit(s, s750::Jogging, jogging_);
  s = withBit(s, s750::Stopping, active && !startLatched_ && !cmd_.run && !jogging_);
  s = withBit(s, s750::SpeedMode, !p_.positionMode);
  s = withBit(s, s750::PositionMode, p_.positionMode);
  s = withBit(s, s750::AtZeroSpeed, outHz_ == 0);
  s = withBit(s, s750::EnableOn, true);
  tx[k750Status] = s;
  const double feedback = p_.positionMode ? profile_.x() : p_.referenceInRpm ? speedRpm_ : outHz_;
  tx[k750Feedback] = rawFromReal(feedback);
}

void PowerFlex::raiseFault(uint16_t number, int64_t nowNs) {
  for (size_t i = 0; i < activeCount_; ++i)
    if (active_[i] == number) {
      causeActive_[i] = true;
      return;
    }
  if (activeCount_ < active_.size()) {
    active_[activeCount_] = number;
    causeActive_[activeCount_++] = true;
  }
  std::copy_backward(queue_.begin(), queue_.end() - 1, queue_.end());
  queue_[0] = number;
  startLatched_ = jogging_ = false;
  startBlocked_ = true;
  outHz_ = 0;  // a fault turns the output off; the motor coasts
  noteFault(nowNs, "F" + std::to_string(number));
}

void PowerFlex::removeFaultCause(uint16_t number) {
  for (size_t i = 0; i < activeCount_; ++i)
    if (active_[i] == number) causeActive_[i] = false;
}

// ClearFaults 0->1: faults whose cause has gone are cleared; the queue keeps them.
void PowerFlex::clearFaults() {
  size_t kept = 0;
  for (size_t i = 0; i < activeCount_; ++i)
    if (causeActive_[i]) {
      active_[kept] = active_[i];
      causeActive_[kept++] = true;
    }
  activeCount_ = kept;
}

void PowerFlex::raiseInjected(Injection& inj, int64_t nowNs) { raiseFault(inj.number, nowNs); }
void PowerFlex::clearInjected(Injection& inj, int64_t nowNs) {
  (void)nowNs;
  removeFaultCause(inj.number);
}

bool PowerFlex::settled() const {
  if (p_.mop && !commLost_ && mop_.moving(cmd_.mopIncrement, cmd_.mopDecrement)) return false;
  if (p_.positionMode) return !coasting_ && !jogging_ && profile_.v() == 0 && (inPosition_ || (!startLatched_ && !cmd_.run));
  return outHz_ == targetHz() && !coasting_;
}

}  // namespace virtcom::drives
