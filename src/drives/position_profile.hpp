#pragma once
// Online trapezoidal setpoint generator of the EPos position loop (docs/universal-axis.md, EPos
// position loop and monitoring). Unlike
// plant/motion_profile.hpp (a move planned once), it is stepped: target, velocity limit,
// acceleration and deceleration may change between two steps (MDI targets on the fly, override
// changes, intermediate stop), and it brakes along the deceleration it is given. Units are the
// caller's (EPos: LU, LU/s, LU/s^2). Pure arithmetic, no allocation.
namespace virtcom::drives {

struct ProfileLimits {
  double vMax = 0;   // >= 0; 0 holds the axis without ending the task (OVERRIDE = 0)
  double accel = 1;  // > 0
  double decel = 1;  // > 0
};

class PositionProfile {
 public:
  void reset(double x) {
    x_ = x;
    v_ = 0;
  }
  // Moves toward `target`; true once the setpoint is at the target at rest (setpoint static).
  bool toPosition(double target, const ProfileLimits& lim, double dtS);
  // Moves toward the signed velocity `vTarget` (|vTarget| is limited by lim.vMax).
  void toVelocity(double vTarget, const ProfileLimits& lim, double dtS);
  double x() const { return x_; }
  double v() const { return v_; }

 private:
  void approach(double vDesired, const ProfileLimits& lim, double dtS);
  double x_ = 0, v_ = 0;
};

}  // namespace virtcom::drives
