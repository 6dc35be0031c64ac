// The EPos setpoint generator (drives/position_profile.hpp) stepped as the drive steps it (1 ms).
#include <gtest/gtest.h>

#include <cmath>

#include "drives/position_profile.hpp"

namespace virtcom::drives {
namespace {

struct Move {
  double distance, vMax, accel;  // LU, LU/s, LU/s^2 (deceleration = acceleration)
};

// Regression test: braking along the continuous sqrt(2 d s) curve, the stepped setpoint passed a
// target approached at full speed (by 125 LU for the gearbox table's 420 mm move) and came back.
TEST(PositionProfile, BrakesOntoTheTargetWithoutPassingIt) {
  constexpr double kDt = 0.001;
  for (const Move& m : {Move{420000, 250000, 500000}, Move{180000, 250000, 500000}, Move{70000, 83333.3, 200000},
                        Move{1000, 5000, 100000}}) {
    SCOPED_TRACE(m.distance);
    PositionProfile p;
    const ProfileLimits lim{m.vMax, m.accel, m.accel};
    int steps = 0;
    double furthest = 0, slowest = 0;
    while (!p.toPosition(m.distance, lim, kDt) && steps < 1'000'000) {
      furthest = std::max(furthest, p.x());
      slowest = std::min(slowest, p.v());
      ++steps;
    }
    EXPECT_LE(furthest, m.distance);
    EXPECT_EQ(slowest, 0.0) << "the setpoint moved backward";
    EXPECT_EQ(p.x(), m.distance);
    // the trapezoid's (or triangle's) time, give or take a few steps
    const double vPeak = std::min(m.vMax, std::sqrt(m.distance * m.accel));
    const double ideal = m.distance / vPeak + vPeak / m.accel;
    EXPECT_NEAR(steps * kDt, ideal, 5 * kDt);
  }
}

}  // namespace
}  // namespace virtcom::drives
