// Trapezoidal and triangular point-to-point profiles against hand-computed values.
#include "plant/motion_profile.hpp"

#include <gtest/gtest.h>

namespace virtcom::plant {
namespace {

TEST(MotionProfile, TrapezoidalMoveAccelCruiseDecel) {
  // 1000 mm at 500 mm/s with 1000 mm/s^2: 0.5 s accel + 1.5 s cruise + 0.5 s decel = 2.5 s.
  MotionProfile p = MotionProfile::plan(1.0, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(p.accelTime, 0.5);
  EXPECT_DOUBLE_EQ(p.cruiseTime, 1.5);
  EXPECT_DOUBLE_EQ(p.totalTime, 2.5);
  EXPECT_FALSE(p.triangular());
  EXPECT_DOUBLE_EQ(p.positionAt(0.5), 0.125);   // a t^2 / 2
  EXPECT_DOUBLE_EQ(p.positionAt(1.0), 0.375);   // + v (t - ta)
  EXPECT_DOUBLE_EQ(p.positionAt(2.5), 1.0);
  EXPECT_DOUBLE_EQ(p.speedAt(1.0), 0.5);
  EXPECT_DOUBLE_EQ(p.speedAt(2.25), 0.25);
  EXPECT_EQ(secondsToNs(p.totalTime), 2'500'000'000);
}

TEST(MotionProfile, ShortMoveIsTriangular) {
  // 100 mm at 500 mm/s, 1000 mm/s^2: v^2/a = 250 mm > 100 mm, ta = sqrt(0.1/1) s, T = 2 ta.
  MotionProfile p = MotionProfile::plan(0.1, 0.5, 1.0);
  EXPECT_TRUE(p.triangular());
  EXPECT_NEAR(p.accelTime, 0.316227766016838, 1e-12);
  EXPECT_NEAR(p.totalTime, 0.632455532033676, 1e-12);
  EXPECT_NEAR(p.peakSpeed, 0.316227766016838, 1e-12);
  EXPECT_NEAR(p.positionAt(p.accelTime), 0.05, 1e-12);
}

TEST(MotionProfile, ExactlyReachingTopSpeedHasNoCruise) {
  MotionProfile p = MotionProfile::plan(0.25, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(p.totalTime, 1.0);
  EXPECT_DOUBLE_EQ(p.cruiseTime, 0.0);
}

TEST(MotionProfile, ZeroDistanceTakesNoTime) {
  MotionProfile p = MotionProfile::plan(0, 0.5, 1.0);
  EXPECT_EQ(p.totalTime, 0);
  EXPECT_EQ(p.positionAt(1), 0);
  EXPECT_EQ(p.speedAt(0), 0);
}

TEST(MotionProfile, PositionIsMonotonicAndClamped) {
  MotionProfile p = MotionProfile::plan(0.7, 0.4, 2.0);
  double last = -1;
  for (int i = -5; i <= 300; ++i) {
    double s = p.positionAt(i * 0.01);
    EXPECT_GE(s, last);
    EXPECT_LE(s, 0.7);
    last = s;
  }
  EXPECT_DOUBLE_EQ(p.positionAt(100), 0.7);
}

}  // namespace
}  // namespace virtcom::plant
