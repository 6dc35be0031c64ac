#pragma once
// Motorised potentiometer (MOP): a setpoint that integrates while "raise" or "lower" is held
// (docs/drive-simulators.md: `mop` of g120 for SINAMICS STW1.13/.14, of powerflex525 for Logic
// Command bits 7/15). Shared by the Siemens and PowerFlex simulators; the caller scales it (rpm or
// Hz).
#include <algorithm>

namespace virtcom::drives {

struct MotorPot {
  double value = 0;    // present MOP setpoint, starts at 0 [S]
  double step = 0;     // change per integration step while raise or lower is held
  double maximum = 0;  // the MOP range is [0, maximum] [S]; direction comes from the drive's own bits

  // Raise and lower together hold the value, as neither does (no preference between them).
  void tick(bool raise, bool lower) {
    if (raise != lower) value = std::clamp(value + (raise ? step : -step), 0.0, maximum);
  }
  // The value would change on the next tick (the device must keep stepping).
  bool moving(bool raise, bool lower) const { return raise != lower && value != (raise ? maximum : 0.0); }
};

}  // namespace virtcom::drives
