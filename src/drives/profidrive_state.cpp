#include "drives/profidrive_state.hpp"

namespace virtcom::drives {

DriveState nextState(DriveState s, const StateInputs& in) {
  using S = DriveState;
  const bool ramping = pulsesEnabled(s);
  if (!in.cmd.noOff2) return S::S1SwitchingOnInhibited;
  if (!in.cmd.noOff3) {
    if (!ramping || (s == S::S5bOff3QuickStop && in.standstill)) return S::S1SwitchingOnInhibited;
    return S::S5bOff3QuickStop;
  }
  if (in.faultActive) {
    if (!ramping || in.faultReaction == Reaction::Off2 || in.standstill) return S::S1SwitchingOnInhibited;
    // OFF1 reaction keeps an OFF3 ramp that is already running.
    return in.faultReaction == Reaction::Off1 && s != S::S5bOff3QuickStop ? S::S5aOff1RampDown : S::S5bOff3QuickStop;
  }
  // An OFF3 ramp completes to S1 even after OFF3 is withdrawn (it is a quick stop, not a pause).
  if (s == S::S5bOff3QuickStop) return in.standstill ? S::S1SwitchingOnInhibited : s;
  if (!in.cmd.enableOperation) {
    if (s == S::S4OperationEnabled) return in.cmd.on ? S::S3ReadyForOperation : S::S2ReadyForSwitchingOn;
    if (s == S::S5aOff1RampDown) return S::S2ReadyForSwitchingOn;  // pulses off: the ramp ends coasting
  }
  if (!in.cmd.on) {
    switch (s) {
      case S::S1SwitchingOnInhibited: return S::S2ReadyForSwitchingOn;
      case S::S3ReadyForOperation: return S::S2ReadyForSwitchingOn;
      case S::S4OperationEnabled: return in.standstill ? S::S2ReadyForSwitchingOn : S::S5aOff1RampDown;
      case S::S5aOff1RampDown: return in.standstill ? S::S2ReadyForSwitchingOn : s;
      default: return s;
    }
  }
  // ON present.
  if (s == S::S1SwitchingOnInhibited) return s;  // needs ON = 0 first
  if (s == S::S5aOff1RampDown) return S::S4OperationEnabled;  // ON returned before standstill [S]
  if (s == S::S2ReadyForSwitchingOn) s = S::S3ReadyForOperation;
  if (s == S::S3ReadyForOperation && in.cmd.enableOperation) s = S::S4OperationEnabled;
  return s;
}

uint16_t stateStatusBits(DriveState s) {
  switch (s) {
    case DriveState::S1SwitchingOnInhibited: return 0x0040;
    case DriveState::S2ReadyForSwitchingOn: return 0x0001;
    case DriveState::S3ReadyForOperation: return 0x0003;
    case DriveState::S4OperationEnabled: return 0x0007;
    case DriveState::S5aOff1RampDown: return 0x0005;
    case DriveState::S5bOff3QuickStop: return 0x0005;
  }
  return 0;
}

const char* stateName(DriveState s) {
  switch (s) {
    case DriveState::S1SwitchingOnInhibited: return "S1";
    case DriveState::S2ReadyForSwitchingOn: return "S2";
    case DriveState::S3ReadyForOperation: return "S3";
    case DriveState::S4OperationEnabled: return "S4";
    case DriveState::S5aOff1RampDown: return "S5a";
    case DriveState::S5bOff3QuickStop: return "S5b";
  }
  return "?";
}

}  // namespace virtcom::drives
