#pragma once
// The PROFIdrive/SINAMICS device state machine S1..S5 (docs/drive-simulators.md, PROFIdrive state
// machine), shared by every Siemens simulator. Pure: the caller supplies the accepted STW1 bits,
// the fault state and whether the motor has come to a standstill; the machine never allocates.
#include <cstdint>

#include "drives/drive_messages.hpp"

namespace virtcom::drives {

enum class DriveState : uint8_t {
  S1SwitchingOnInhibited,
  S2ReadyForSwitchingOn,
  S3ReadyForOperation,
  S4OperationEnabled,
  S5aOff1RampDown,
  S5bOff3QuickStop,
};

// The STW1 bits 0..3 common to every PROFIdrive control word.
struct StateCommand {
  bool on = false, noOff2 = false, noOff3 = false, enableOperation = false;
};

struct StateInputs {
  StateCommand cmd;
  Reaction faultReaction = Reaction::None;  // strongest reaction of the active faults
  bool faultActive = false;
  bool standstill = false;                  // |n_act| < p1226 for p1228
};

// One evaluation after an accepted frame or a tick. Priorities when several conditions hold:
// OFF2 > OFF3 > fault reaction > inhibit operation > OFF1 > ON. A fault ends in S1 (through
// its ramp when the reaction is OFF1/OFF3 and the pulses were on). S2 -> S3 -> S4 may happen
// in one evaluation when ON and enable operation arrive together.
DriveState nextState(DriveState s, const StateInputs& in);

constexpr bool pulsesEnabled(DriveState s) {
  return s == DriveState::S4OperationEnabled || s == DriveState::S5aOff1RampDown || s == DriveState::S5bOff3QuickStop;
}
// ZSW1 bits 0, 1, 2 and 6 of a state (bits 3/4/5/7 are added by the caller).
uint16_t stateStatusBits(DriveState s);
const char* stateName(DriveState s);

}  // namespace virtcom::drives
