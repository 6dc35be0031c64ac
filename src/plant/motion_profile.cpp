#include "plant/motion_profile.hpp"

#include <cmath>

namespace virtcom::plant {

MotionProfile MotionProfile::plan(double distance, double vMax, double accel) {
  MotionProfile p;
  p.distance = distance > 0 ? distance : 0;
  p.vMax = vMax;
  p.accel = accel;
  if (p.distance == 0 || vMax <= 0 || accel <= 0) return p;
  const double rampDistance = vMax * vMax / accel;  // accelerate + decelerate at full speed
  if (p.distance >= rampDistance) {
    p.peakSpeed = vMax;
    p.accelTime = vMax / accel;
    p.cruiseTime = (p.distance - rampDistance) / vMax;
  } else {
    p.accelTime = std::sqrt(p.distance / accel);
    p.peakSpeed = accel * p.accelTime;
    p.cruiseTime = 0;
  }
  p.totalTime = 2 * p.accelTime + p.cruiseTime;
  return p;
}

double MotionProfile::positionAt(double t) const {
  if (t <= 0) return 0;
  if (t >= totalTime) return distance;
  const double ta = accelTime;
  if (t < ta) return 0.5 * accel * t * t;
  const double sAccel = 0.5 * accel * ta * ta;
  if (t < ta + cruiseTime) return sAccel + peakSpeed * (t - ta);
  const double remaining = totalTime - t;
  const double s = distance - 0.5 * accel * remaining * remaining;
  return s < 0 ? 0 : s;
}

double MotionProfile::speedAt(double t) const {
  if (t <= 0 || t >= totalTime) return 0;
  if (t < accelTime) return accel * t;
  if (t < accelTime + cruiseTime) return peakSpeed;
  return accel * (totalTime - t);
}

int64_t secondsToNs(double seconds) { return static_cast<int64_t>(std::llround(seconds * 1e9)); }

}  // namespace virtcom::plant
