#pragma once
// Telegram 111 word slots and bits used by the EPos simulator, resolved from the tables at
// compile time (a misspelt name fails to compile). Shared by epos_axis.cpp and epos_modes.cpp.
#include "drives/telegram.hpp"

namespace virtcom::drives::epos {

constexpr uint8_t rxWord(std::string_view n) { return wordSlot(TelegramId::Std111, Dir::ToDrive, n).index; }
constexpr uint8_t txWord(std::string_view n) { return wordSlot(TelegramId::Std111, Dir::FromDrive, n).index; }

inline constexpr uint8_t kStw1 = rxWord("STW1"), kPosStw1 = rxWord("POS_STW1"), kPosStw2 = rxWord("POS_STW2"),
                         kStw2 = rxWord("STW2"), kOverride = rxWord("OVERRIDE"), kTarPos = rxWord("MDI_TARPOS"),
                         kVelocity = rxWord("MDI_VELOCITY"), kAcc = rxWord("MDI_ACC"), kDec = rxWord("MDI_DEC");
inline constexpr uint8_t kZsw1 = txWord("ZSW1"), kPosZsw1 = txWord("POS_ZSW1"), kPosZsw2 = txWord("POS_ZSW2"),
                         kZsw2 = txWord("ZSW2"), kMeldw = txWord("MELDW"), kXist = txWord("XIST_A"),
                         kNistB = txWord("NIST_B"), kFaultCode = txWord("FAULT_CODE"), kWarnCode = txWord("WARN_CODE");

namespace stw1 {
inline constexpr BitDef On = bitDef(Layout::Stw1Pos, "On"), NoOff2 = bitDef(Layout::Stw1Pos, "NoOff2"),
                        NoOff3 = bitDef(Layout::Stw1Pos, "NoOff3"), EnableOperation = bitDef(Layout::Stw1Pos, "EnableOperation"),
                        NoReject = bitDef(Layout::Stw1Pos, "NoRejectTask"),
                        NoIntermediateStop = bitDef(Layout::Stw1Pos, "NoIntermediateStop"),
                        ActivateTask = bitDef(Layout::Stw1Pos, "ActivateTask"), AckFault = bitDef(Layout::Stw1Pos, "AckFault"),
                        Jog1 = bitDef(Layout::Stw1Pos, "Jog1"), Jog2 = bitDef(Layout::Stw1Pos, "Jog2"),
                        ControlByPlc = bitDef(Layout::Stw1Pos, "ControlByPlc"),
                        StartReferencing = bitDef(Layout::Stw1Pos, "StartReferencing"),
                        ExternalBlockChange = bitDef(Layout::Stw1Pos, "ExternalBlockChange");
}
namespace pos1 {
inline constexpr BitDef Block = bitDef(Layout::PosStw1, "BlockNumber"), Absolute = bitDef(Layout::PosStw1, "AbsoluteMode"),
                        DirPositive = bitDef(Layout::PosStw1, "DirPositive"), DirNegative = bitDef(Layout::PosStw1, "DirNegative"),
                        Continuous = bitDef(Layout::PosStw1, "ContinuousTransfer"), Setup = bitDef(Layout::PosStw1, "SetupMode"),
                        Mdi = bitDef(Layout::PosStw1, "MdiSelect");
}
namespace pos2 {
inline constexpr BitDef SetReference = bitDef(Layout::PosStw2, "SetReferencePoint"),
                        IncrementalJog = bitDef(Layout::PosStw2, "IncrementalJog"),
                        Flying = bitDef(Layout::PosStw2, "FlyingReferencing"), RefNegative = bitDef(Layout::PosStw2, "RefStartNegative"),
                        Probe2 = bitDef(Layout::PosStw2, "Probe2"), ProbeFalling = bitDef(Layout::PosStw2, "ProbeFallingEdge"),
                        SoftwareLimits = bitDef(Layout::PosStw2, "SoftwareLimits");
}
namespace stw2 {
inline constexpr BitDef DataSet = bitDef(Layout::Stw2, "DataSet"), MasterSol = bitDef(Layout::Stw2, "MasterSignOfLife");
}
namespace zsw1 {
inline constexpr BitDef Fault = bitDef(Layout::Zsw1Pos, "FaultActive"), NoOff2 = bitDef(Layout::Zsw1Pos, "NoOff2Active"),
                        NoOff3 = bitDef(Layout::Zsw1Pos, "NoOff3Active"), Alarm = bitDef(Layout::Zsw1Pos, "AlarmActive"),
                        NoFollowingError = bitDef(Layout::Zsw1Pos, "NoFollowingError"),
                        ControlRequested = bitDef(Layout::Zsw1Pos, "ControlRequested"),
                        TargetReached = bitDef(Layout::Zsw1Pos, "TargetReached"), ReferenceSet = bitDef(Layout::Zsw1Pos, "ReferenceSet"),
                        TaskAck = bitDef(Layout::Zsw1Pos, "TaskAck"), Standstill = bitDef(Layout::Zsw1Pos, "Standstill"),
                        Accelerating = bitDef(Layout::Zsw1Pos, "Accelerating"), Decelerating = bitDef(Layout::Zsw1Pos, "Decelerating");
}
namespace pzsw1 {
inline constexpr BitDef Block = bitDef(Layout::PosZsw1, "ActiveBlock"), Jog = bitDef(Layout::PosZsw1, "JogActive"),
                        RefApproach = bitDef(Layout::PosZsw1, "RefApproachActive"), Flying = bitDef(Layout::PosZsw1, "FlyingRefActive"),
                        Blocks = bitDef(Layout::PosZsw1, "BlocksActive"), Setup = bitDef(Layout::PosZsw1, "SetupActive"),
                        Mdi = bitDef(Layout::PosZsw1, "MdiPositioningActive");
}
namespace pzsw2 {
inline constexpr BitDef SetpointStatic = bitDef(Layout::PosZsw2, "SetpointStatic"), Forward = bitDef(Layout::PosZsw2, "MovesForward"),
                        Backward = bitDef(Layout::PosZsw2, "MovesBackward"), LimitMinus = bitDef(Layout::PosZsw2, "SwLimitMinus"),
                        LimitPlus = bitDef(Layout::PosZsw2, "SwLimitPlus"), Out1 = bitDef(Layout::PosZsw2, "DirectOutput1"),
                        Out2 = bitDef(Layout::PosZsw2, "DirectOutput2"), TaskActive = bitDef(Layout::PosZsw2, "TaskActive"),
                        VelocityLimiting = bitDef(Layout::PosZsw2, "VelocityLimiting");
}
namespace zsw2 {
inline constexpr BitDef DataSet = bitDef(Layout::Zsw2, "ActiveDataSet"), Pulses = bitDef(Layout::Zsw2, "PulsesEnabled"),
                        SlaveSol = bitDef(Layout::Zsw2, "SlaveSignOfLife");
}
namespace meldw {
inline constexpr BitDef RampDone = bitDef(Layout::Meldw, "RampDone"), TorqueBelow = bitDef(Layout::Meldw, "TorqueBelowThreshold"),
                        Below2161 = bitDef(Layout::Meldw, "SpeedBelowP2161"), Below2155 = bitDef(Layout::Meldw, "SpeedBelowP2155"),
                        NoMotorOvertemp = bitDef(Layout::Meldw, "NoMotorOvertemp"),
                        NoPowerUnitOvertemp = bitDef(Layout::Meldw, "NoPowerUnitOvertemp"),
                        SpeedOk = bitDef(Layout::Meldw, "SpeedWithinTolerance"), Controller = bitDef(Layout::Meldw, "ControllerEnabled"),
                        Ready = bitDef(Layout::Meldw, "DriveReady"), Pulses = bitDef(Layout::Meldw, "PulsesEnabled");
}

}  // namespace virtcom::drives::epos
