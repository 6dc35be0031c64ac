#pragma once
// Point-to-point motion with a trapezoidal velocity profile (accelerate at `a`, cruise at
// `vMax`, decelerate at `a`), falling back to a triangular profile when the distance is too
// short to reach `vMax`. All quantities in SI (m, m/s, m/s^2, s). Pure arithmetic: no
// allocation, usable on the per-tick path.
#include <cstdint>

namespace virtcom::plant {

struct MotionProfile {
  double distance = 0;    // m, >= 0
  double vMax = 0;        // m/s, > 0
  double accel = 0;       // m/s^2, > 0
  double peakSpeed = 0;   // m/s actually reached (== vMax unless triangular)
  double accelTime = 0;   // s, duration of the acceleration phase (== deceleration phase)
  double cruiseTime = 0;  // s, 0 for a triangular profile
  double totalTime = 0;   // s

  // Plans a move of `distance` (>= 0). Trapezoidal: ta = v/a, tc = (d - v^2/a)/v, T = 2ta + tc;
  // triangular when d < v^2/a: ta = sqrt(d/a), T = 2ta.
  static MotionProfile plan(double distance, double vMax, double accel);
  // Distance travelled at `t` seconds after the start, clamped to [0, distance].
  double positionAt(double t) const;
  // Speed (>= 0) at `t` seconds after the start; 0 outside the move.
  double speedAt(double t) const;
  bool triangular() const { return cruiseTime == 0 && distance > 0; }
};

// Seconds to integer nanoseconds, rounded to nearest (durations stay exact for decimal inputs).
int64_t secondsToNs(double seconds);

}  // namespace virtcom::plant
