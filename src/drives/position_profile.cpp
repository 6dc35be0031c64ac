#include "drives/position_profile.hpp"

#include <algorithm>
#include <cmath>

namespace virtcom::drives {

// Speeding up (same sign, larger magnitude) uses `accel`; everything else, including a
// reversal through zero, brakes with `decel`.
void PositionProfile::approach(double vDesired, const ProfileLimits& lim, double dtS) {
  const bool speedingUp = std::abs(vDesired) > std::abs(v_) && vDesired * v_ >= 0;
  const double step = (speedingUp ? lim.accel : lim.decel) * dtS;
  v_ = v_ < vDesired ? std::min(vDesired, v_ + step) : std::max(vDesired, v_ - step);
}

bool PositionProfile::toPosition(double target, const ProfileLimits& lim, double dtS) {
  const double s = target - x_;
  if (s == 0 && v_ == 0) return true;
  // The fastest speed from which the axis still stops at the target in this stepping: braking
  // from v by decel x dt per step, moving at each step's new speed, covers v^2/(2 decel) +
  // v dt/2. (Braking along the continuous sqrt(2 decel s), the stepped speed trails that curve:
  // a target approached at full speed was passed and then approached from the other side.)
  const double halfStep = 0.5 * lim.decel * dtS;
  const double reachable = std::sqrt(halfStep * halfStep + 2.0 * lim.decel * std::abs(s)) - halfStep;
  approach(std::copysign(std::min(lim.vMax, reachable), s), lim, dtS);
  const double next = x_ + v_ * dtS;
  // Arrival: the step would reach or pass the target while approaching it slowly enough that
  // the remaining speed is within one braking step (no jump for a normal approach).
  const bool passes = (target - next) * s <= 0 && v_ * s > 0;
  if (passes && std::abs(v_) <= 2.0 * lim.decel * dtS + 1e-9) {
    x_ = target;
    v_ = 0;
    return true;
  }
  x_ = next;
  return false;
}

void PositionProfile::toVelocity(double vTarget, const ProfileLimits& lim, double dtS) {
  approach(std::clamp(vTarget, -lim.vMax, lim.vMax), lim, dtS);
  x_ += v_ * dtS;
}

}  // namespace virtcom::drives
