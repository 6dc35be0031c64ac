// EposAxis modes (docs/universal-axis.md, EPos modes): which function a received frame selects, and
// how each one moves the position setpoint every integration step.
#include <algorithm>
#include <cmath>

#include "drives/epos_axis.hpp"
#include "drives/epos_words.hpp"

namespace virtcom::drives {

using namespace epos;

namespace {
constexpr uint16_t kNotReferenced = 7461, kNoSuchBlock = 7462, kLimitMinus = 7479, kLimitPlus = 7480;
constexpr uint16_t kCamNotFound = 7458;
constexpr double kQ14 = 16384.0;
}  // namespace

// v_max = min(velocity x OVERRIDE, p2571); a, d = p2572/p2573 x override (docs/universal-axis.md,
// EPos position loop and monitoring).
ProfileLimits EposAxis::limits(double velocity1000LuMin, double accelPercent, double decelPercent) const {
  ProfileLimits l;
  const double v = std::min(std::abs(velocity1000LuMin) * override_ / kQ14, p_.p2571);
  l.vMax = v * 1000.0 / 60.0;
  l.accel = std::max(p_.p2572 * 1000.0 * accelPercent / 100.0, 1.0);
  l.decel = std::max(p_.p2573 * 1000.0 * decelPercent / 100.0, 1.0);
  return l;
}

const ProfileLimits& EposAxis::taskLimits() {
  LimitsMemo& m = taskLimits_;
  if (m.velocity != taskVelocity_ || m.acc != taskAcc_ || m.dec != taskDec_ || m.override != override_)
    m = {taskVelocity_, taskAcc_, taskDec_, override_, limits(taskVelocity_, taskAcc_, taskDec_)};
  return m.lim;
}

double EposAxis::clampToSoftwareLimits(double machineTarget) const {
  if (!test(posStw2_, pos2::SoftwareLimits)) return machineTarget;
  return std::clamp(machineTarget + offset_, p_.p2580, p_.p2581) - offset_;
}

// Velocity modes (setup, jog, endless blocks) stop exactly at an active software limit: once
// the braking distance reaches it, the limit becomes a position target.
void EposAxis::moveAtVelocity(double v, const ProfileLimits& lim, double dtS) {
  if (test(posStw2_, pos2::SoftwareLimits) && v != 0) {
    const double limit = (v > 0 ? p_.p2581 : p_.p2580) - offset_;
    const double room = (limit - profile_.x()) * (v > 0 ? 1 : -1);
    const double speed = std::abs(profile_.v());
    if (room <= speed * speed / (2.0 * lim.decel) + speed * dtS) {
      profile_.toPosition(limit, lim, dtS);
      return;
    }
  }
  profile_.toVelocity(v, lim, dtS);
}

void EposAxis::selectMode(uint32_t previous, uint32_t previousPos2, int64_t nowNs) {
  const bool jog1 = test(stw1_, stw1::Jog1), jog2 = test(stw1_, stw1::Jog2);
  const bool ref = test(stw1_, stw1::StartReferencing), flying = test(posStw2_, pos2::Flying);
  const bool mdi = test(posStw1_, pos1::Mdi);
  const bool taskEdge = test(stw1_, stw1::ActivateTask) && !test(previous, stw1::ActivateTask);
  if (!ref) refLatched_ = false;
  if (!jog1 && !jog2) jogLatched_ = false;

  // Levels whose withdrawal ends the running function (braking to standstill first).
  switch (mode_) {
    case Mode::Jog: stopping_ = stopping_ || jog1 == jog2 || jog2 != jogBit2_; break;
    case Mode::JogIncremental: stopping_ = stopping_ || !(jogBit2_ ? jog2 : jog1); break;
    case Mode::ReferenceApproach: stopping_ = stopping_ || !ref; break;
    case Mode::MdiPositioning:
    case Mode::MdiSetup: stopping_ = stopping_ || !mdi; break;
    default: break;
  }
  flyingArmed_ = ref && flying && !refLatched_;

  const bool idle = mode_ == Mode::None || (profile_.v() == 0 && setpointStatic_ && !stopping_);
  if (test(posStw2_, pos2::SetReference) && !test(previousPos2, pos2::SetReference) && idle && profile_.v() == 0) {
    setReference(machinePos_);  // ignored while moving (EPos modes)
    return;
  }
  if (stopping_) return;
  if (ref && !flying && !refLatched_ && mode_ != Mode::ReferenceApproach) {
    if (idle) startReferencing();
    return;
  }
  if (jog1 != jog2 && mode_ != Mode::Jog && mode_ != Mode::JogIncremental) {
    const bool incremental = test(posStw2_, pos2::IncrementalJog);
    if (idle && !(incremental && jogLatched_)) startJog(jog2, incremental);
    return;  // refused while another task moves (EPos modes: jog)
  }
  const bool mdiMode = mode_ == Mode::MdiPositioning || mode_ == Mode::MdiSetup;
  if (mdi && (taskEdge || (mdiMode && test(posStw1_, pos1::Continuous))) && (idle || mdiMode)) startMdi(nowNs);
  else if (!mdi && taskEdge && idle) startBlock(static_cast<uint8_t>(field(posStw1_, pos1::Block)), nowNs);
}

void EposAxis::acceptTask() {
  taskAck_ = !taskAck_;
  stopping_ = false;
  alarms_.clear(kNotReferenced, nowNs_);
  alarms_.clear(kNoSuchBlock, nowNs_);
}

void EposAxis::startMdi(int64_t nowNs) {
  if (test(posStw1_, pos1::Setup)) {
    mode_ = Mode::MdiSetup;
    taskVelocity_ = mdiVelocity_;
    taskAcc_ = mdiAcc_ * 100.0 / kQ14, taskDec_ = mdiDec_ * 100.0 / kQ14;
    acceptTask();
    return;
  }
  const bool absolute = test(posStw1_, pos1::Absolute);
  if (absolute && !referenced_) {  // not referenced: alarm, no motion (EPos modes)
    alarms_.raise(kNotReferenced, 0, nowNs);
    return;
  }
  // Relative: from the actual position at acceptance [S]; repeated edges add the distance again.
  const double target = absolute ? mdiTarget_ - offset_ : machinePos_ + mdiTarget_;
  mode_ = Mode::MdiPositioning;
  target_ = clampToSoftwareLimits(target);
  setpointStatic_ = setpointStatic_ && target_ == profile_.x();
  taskVelocity_ = mdiVelocity_;
  taskAcc_ = mdiAcc_ * 100.0 / kQ14, taskDec_ = mdiDec_ * 100.0 / kQ14;
  acceptTask();
}

void EposAxis::startJog(bool jog2, bool incremental) {
  const double velocity = jog2 ? p_.p2586 : p_.p2585;
  direction_ = velocity >= 0 ? 1 : -1;
  taskVelocity_ = std::abs(velocity);
  taskAcc_ = taskDec_ = 100;
  jogBit2_ = jog2;
  stopping_ = false;
  mode_ = incremental ? Mode::JogIncremental : Mode::Jog;
  if (incremental) {
    jogLatched_ = true;
    target_ = clampToSoftwareLimits(profile_.x() + direction_ * (jog2 ? p_.p2588 : p_.p2587));
  }
  setpointStatic_ = false;
}

void EposAxis::startReferencing() {
  mode_ = Mode::ReferenceApproach;
  referenced_ = false;
  refDir_ = test(posStw2_, pos2::RefNegative) ? -1 : 1;  // only POS_STW2.9 decides (EPos modes)
  refPhase_ = p_.hasRefCam ? 1 : 2;
  refStart_ = profile_.x();
  taskAcc_ = taskDec_ = 100;
  stopping_ = false;
  setpointStatic_ = false;
}

void EposAxis::setReference(double machinePos) {
  offset_ = p_.p2599 - machinePos;
  referenced_ = true;
  alarms_.clear(kNotReferenced, nowNs_);
}

void EposAxis::endTask() {
  mode_ = Mode::None;
  stopping_ = false;
  waitUntilNs_ = -1;
  target_ = profile_.x();
  setpointStatic_ = profile_.v() == 0;
}

void EposAxis::startBlock(uint8_t number, int64_t nowNs) {
  for (size_t i = 0; i < p_.blocks.size(); ++i) {
    if (p_.blocks[i].number != number) continue;
    acceptTask();
    mode_ = Mode::Blocks;
    beginBlock(i, 0);
    return;
  }
  alarms_.raise(kNoSuchBlock, number, nowNs);  // unknown block: no motion (EPos modes)
}

// Sets up block `index`; GOTO and output tasks complete at once (depth bounds a GOTO loop).
void EposAxis::beginBlock(size_t index, int depth) {
  const TraversingBlock& b = p_.blocks[index];
  blockIndex_ = index;
  block_ = b.number;
  externalChange_ = false;
  taskVelocity_ = b.velocity;
  taskAcc_ = b.accelPercent, taskDec_ = b.decelPercent;
  setpointStatic_ = false;
  using Task = TraversingBlock::Task;
  switch (b.task) {
    case Task::PositionAbs:
      if (!referenced_) {
        alarms_.raise(kNotReferenced, 0, nowNs_);
        endTask();
        return;
      }
      target_ = clampToSoftwareLimits(b.position - offset_);
      return;
    case Task::PositionRel: target_ = clampToSoftwareLimits(profile_.x() + b.position); return;
    case Task::EndlessPos: direction_ = 1; return;
    case Task::EndlessNeg: direction_ = -1; return;
    case Task::Wait: waitUntilNs_ = nowNs_ + int64_t{b.parameter} * 1'000'000; return;
    case Task::Goto:
      for (size_t i = 0; i < p_.blocks.size(); ++i)
        if (p_.blocks[i].number == b.parameter && depth < 64) return beginBlock(i, depth + 1);
      endTask();
      return;
    case Task::SetOutput:
    case Task::ResetOutput: {
      const bool on = b.task == Task::SetOutput;
      if (b.parameter & 1) output1_ = on;
      if (b.parameter & 2) output2_ = on;
      if (depth < 64) blockDone(depth + 1);
      return;
    }
  }
}

// The running block has completed: continue per its advance condition (docs/universal-axis.md, EPos
// modes).
void EposAxis::blockDone(int depth) {
  using Advance = TraversingBlock::Advance;
  const TraversingBlock& b = p_.blocks[blockIndex_];
  waitUntilNs_ = -1;
  if (b.advance == Advance::ContinueExternal && !externalChange_) return;  // wait for STW1.13
  if (b.advance == Advance::End || blockIndex_ + 1 >= p_.blocks.size()) {
    endTask();
    return;
  }
  beginBlock(blockIndex_ + 1, depth);
}

void EposAxis::blockStep(const ProfileLimits& lim, double dtS) {
  using Task = TraversingBlock::Task;
  const TraversingBlock& b = p_.blocks[blockIndex_];
  switch (b.task) {
    case Task::PositionAbs:
    case Task::PositionRel:
      setpointStatic_ = profile_.toPosition(target_, lim, dtS);
      if (setpointStatic_) blockDone(0);
      return;
    case Task::EndlessPos:
    case Task::EndlessNeg:
      moveAtVelocity(direction_ * lim.vMax, lim, dtS);
      if (externalChange_) blockDone(0);
      return;
    case Task::Wait:
      if (nowNs_ >= waitUntilNs_) blockDone(0);
      return;
    default: blockDone(0); return;  // waiting for an external change after an output task
  }
}

// Reference point approach [S simplified] (docs/universal-axis.md, EPos modes): (1) cam search at
// p2605, (2) on to the next zero mark at p2608, (3) the reference point offset p2600 at p2611;
// there x := p2599.
void EposAxis::referencingStep(double dtS) {
  if (refPhase_ == 1) {
    const ProfileLimits lim = limits(p_.p2605, 100, 100);
    profile_.toVelocity(refDir_ * lim.vMax, lim, dtS);
    if (refDir_ * (profile_.x() - p_.refCamPos) >= 0) refPhase_ = 2;
    if (p_.p2606 > 0 && std::abs(profile_.x() - refStart_) > p_.p2606) {
      raiseFault(kCamNotFound, Reaction::Off1, nowNs_);
      faults_.causeGone(kCamNotFound);
      refLatched_ = true;
      stopping_ = true;
    }
    return;
  }
  if (refPhase_ == 2) {
    const ProfileLimits lim = limits(p_.p2608, 100, 100);
    const double before = profile_.x();
    profile_.toVelocity(refDir_ * lim.vMax, lim, dtS);
    const double k0 = std::floor((before - p_.zeroMarkPos) / p_.zeroMarkPitch);
    const double k1 = std::floor((profile_.x() - p_.zeroMarkPos) / p_.zeroMarkPitch);
    // A zero mark is only detected at the approach velocity, after braking from the cam search.
    if (k0 != k1 && std::abs(profile_.v()) <= lim.vMax + 1e-9) {
      const double mark = p_.zeroMarkPos + std::max(k0, k1) * p_.zeroMarkPitch;
      target_ = mark + p_.p2600;
      refPhase_ = 3;
    }
    return;
  }
  if (profile_.toPosition(target_, limits(p_.p2611, 100, 100), dtS)) {
    setReference(target_);
    refLatched_ = true;
    endTask();
  }
}

void EposAxis::checkFlyingProbe(double before, double after) {
  if (!flyingArmed_) return;
  const double probe = p_.probePos[test(posStw2_, pos2::Probe2) ? 1 : 0];
  const bool hit = test(posStw2_, pos2::ProbeFalling) ? (before > probe && after <= probe) : (before < probe && after >= probe);
  if (!hit) return;
  offset_ = p_.p2599 - probe;  // flying referencing: x := p2599 + (x_act - x_probe)
  referenced_ = true;
  flyingArmed_ = false;
  refLatched_ = true;
}

void EposAxis::motion(double dtS) {
  if (!pulsesEnabled(state_)) {
    if (taskActive()) endTask();
    setpointStatic_ = true;
    return;
  }
  ProfileLimits lim = taskLimits();
  const bool reject = !test(stw1_, stw1::NoReject);
  if (state_ != DriveState::S4OperationEnabled || faults_.active() || stopping_ || reject || mode_ == Mode::None) {
    // Brake: state-machine stops and rejected tasks with 100 % of p2573 (EPos modes).
    if (state_ != DriveState::S4OperationEnabled || faults_.active() || reject) lim.decel = p_.p2573 * 1000.0;
    if (profile_.v() != 0 || taskActive()) {
      profile_.toVelocity(0, lim, dtS);
      setpointStatic_ = false;
      if (profile_.v() == 0) endTask();
    }
  } else if (!test(stw1_, stw1::NoIntermediateStop) && mode_ != Mode::Jog && mode_ != Mode::JogIncremental) {
    profile_.toVelocity(0, lim, dtS);  // intermediate stop: the task stays pending
    setpointStatic_ = false;
  } else {
    switch (mode_) {
      case Mode::MdiPositioning: setpointStatic_ = profile_.toPosition(target_, lim, dtS); break;
      case Mode::MdiSetup: {
        const bool plus = test(posStw1_, pos1::DirPositive), minus = test(posStw1_, pos1::DirNegative);
        const int dir = plus == minus ? 0 : (plus ? 1 : -1);
        moveAtVelocity(dir * lim.vMax, lim, dtS);
        setpointStatic_ = dir == 0 && profile_.v() == 0;
        if (setpointStatic_) target_ = profile_.x();
        break;
      }
      case Mode::Jog: moveAtVelocity(direction_ * lim.vMax, lim, dtS); break;
      case Mode::JogIncremental: setpointStatic_ = profile_.toPosition(target_, lim, dtS); break;
      case Mode::ReferenceApproach: referencingStep(dtS); break;
      case Mode::Blocks: blockStep(lim, dtS); break;
      case Mode::None: break;
    }
  }
  updateLimitFlags();
}

void EposAxis::updateLimitFlags() {
  const bool active = test(posStw2_, pos2::SoftwareLimits);
  const double reported = profile_.x() + offset_;
  const bool plus = active && reported >= p_.p2581 - 0.5, minus = active && reported <= p_.p2580 + 0.5;
  if (plus != swLimitPlus_) plus ? (void)alarms_.raise(kLimitPlus, 0, nowNs_) : alarms_.clear(kLimitPlus, nowNs_);
  if (minus != swLimitMinus_) minus ? (void)alarms_.raise(kLimitMinus, 0, nowNs_) : alarms_.clear(kLimitMinus, nowNs_);
  swLimitPlus_ = plus, swLimitMinus_ = minus;
}

}  // namespace virtcom::drives
