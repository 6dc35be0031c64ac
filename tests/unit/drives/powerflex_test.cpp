// PowerFlex 525 / 750: acceptance scenarios of docs/drive-simulators.md seen from the drive, with
// raw logic words (P044 = 60 Hz, P041 = P042 = 10 s, one pole pair: 1 Hz = 60 rpm).
#include <gtest/gtest.h>

#include "drive_rig.hpp"

namespace virtcom::drives {
namespace {

constexpr uint16_t kStartForward = 0x0012, kStartReverse = 0x0022, kStop = 0x0001, kClearFaults = 0x0008;

TEST(PowerFlex525, E18ForwardAt1188CentiHz) {
  PowerFlexRig rig;
  rig.cmd(kClearFaults, 0);
  rig.cmd(0, 0);
  EXPECT_EQ(rig.status() & 0x01FF, 0x000D);  // ready, forward (commanded and at standstill), not active
  rig.cmd(kStartForward, 1188, 1500);        // 11.88 Hz at 6 Hz/s: 2 s
  EXPECT_EQ(rig.outputFreq(), 1188);
  EXPECT_EQ(rig.status() & 0x01FF, 0x010F);  // Ready, Active, CommandDir, ActualDir, AtReference
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), 712.8, 1e-9);
}

TEST(PowerFlex525, E19ReverseReportsMagnitudeAndActualDir) {
  PowerFlexRig rig;
  rig.cmd(kStartReverse, 1188, 1500);
  EXPECT_EQ(rig.outputFreq(), 1188);
  EXPECT_EQ(rig.status() & 0x01FF, 0x0103);  // Ready, Active, AtReference; both directions 0
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), -712.8, 1e-9);
}

TEST(PowerFlex525, E20E21JogSpeedThroughTheSpeedBits) {
  PowerFlexRig fwd;
  fwd.cmd(kStartForward, 475, 1000);
  EXPECT_EQ(fwd.outputFreq(), 475);
  EXPECT_NEAR(fwd.drive->shaftSpeedRpm(), 285.0, 1e-9);
  PowerFlexRig rev;
  rev.cmd(kStartReverse, 475, 1000);
  EXPECT_EQ(rev.outputFreq(), 475);
  EXPECT_FALSE(rev.status() & 0x0008);
  EXPECT_NEAR(rev.drive->shaftSpeedRpm(), -285.0, 1e-9);
}

TEST(PowerFlex525, RampsWithAccelTimeOneAndReversesThroughZero) {
  PowerFlexRig rig;
  rig.cmd(kStartForward, 1000, 250);  // 0.5 s at 6 Hz/s = 3 Hz
  EXPECT_NEAR(rig.outputFreq(), 300, 1);
  EXPECT_TRUE(rig.status() & 0x0010);  // accelerating
  EXPECT_FALSE(rig.status() & 0x0100);
  rig.cmd(kStartForward, 1000, 1000);
  rig.cmd(0x0020, 1000, 500);          // reverse only (Start latched): 10 Hz -> 4 Hz
  EXPECT_NEAR(rig.outputFreq(), 400, 1);
  EXPECT_TRUE(rig.status() & 0x0008);  // still rotating forward
  EXPECT_FALSE(rig.status() & 0x0004); // commanded reverse
  EXPECT_TRUE(rig.status() & 0x0020);  // decelerating
  rig.cmd(0x0020, 1000, 1500);
  EXPECT_EQ(rig.outputFreq(), 1000);
  EXPECT_FALSE(rig.status() & 0x0008);
}

TEST(PowerFlex525, AccelTimeTwoSelectedByTheRateField) {
  PowerFlexParams p;
  p.accel2S = 1.0;  // 60 Hz/s
  PowerFlexRig rig(TelegramId::Pf525, p);
  rig.cmd(kStartForward | 0x0200, 1000, 50);  // AccelRate = 10: time 2; 0.1 s -> 6 Hz
  EXPECT_NEAR(rig.outputFreq(), 600, 15);  // 98 ms of ramp after the first frame
}

TEST(PowerFlex525, PresetFrequencyByFreqSelect) {
  PowerFlexRig rig;
  rig.cmd(kStartForward | 0x6000, 1000, 2000);  // 110: preset 2 (A412 = 10 Hz)
  EXPECT_EQ(rig.outputFreq(), 1000);
  EXPECT_FALSE(rig.status() & 0x0200);          // reference not from comm
  rig.cmd(kStartForward | 0x7000, 1000, 2000);  // 111: preset 3 (A413 = 20 Hz)
  EXPECT_EQ(rig.outputFreq(), 2000);
}

TEST(PowerFlex525, StopRampsToZeroThenInactive) {
  PowerFlexRig rig;
  rig.cmd(kStartForward, 600, 1000);
  rig.cmd(kStop, 600, 250);               // 6 Hz at 6 Hz/s decel: 1 s
  EXPECT_GT(rig.outputFreq(), 0);
  EXPECT_TRUE(rig.status() & 0x0002);
  rig.cmd(kStop, 600, 300);
  EXPECT_EQ(rig.outputFreq(), 0);
  EXPECT_FALSE(rig.status() & 0x0002);
  rig.cmd(0, 600, 100);                    // Start latch was cleared by Stop
  EXPECT_EQ(rig.outputFreq(), 0);
}

TEST(PowerFlex525, E32StartInterlockAndClearFaultEdge) {
  PowerFlexRig rig;
  rig.cmd(kStop | 0x0002 | 0x0010, 600, 100);  // Stop and Start together: stays stopped
  EXPECT_EQ(rig.outputFreq(), 0);
  EXPECT_FALSE(rig.status() & 0x0002);
  rig.cmd(kStartForward, 600, 100);            // Stop 1 -> 0 with Start held: starts
  EXPECT_GT(rig.outputFreq(), 0);
  rig.cmd(kStartForward | kClearFaults, 600, 5);  // ClearFaults held at 1 ...
  rig.drive->raiseFault(7, rig.nowNs);            // ... while a new fault occurs
  rig.drive->removeFaultCause(7);
  rig.cmd(kStartForward | kClearFaults, 600, 5);
  EXPECT_TRUE(rig.status() & 0x0080);
  EXPECT_FALSE(rig.status() & 0x0001);
  rig.cmd(kStartForward, 600);
  rig.cmd(kStartForward | kClearFaults, 600);      // 0 -> 1 clears
  EXPECT_FALSE(rig.status() & 0x0080);
  EXPECT_EQ(rig.drive->faultQueue()[0], 7);        // the queue keeps the history
  rig.cmd(kStartForward, 600, 100);                // Start still held: needs a new Start
  EXPECT_EQ(rig.outputFreq(), 0);
  rig.cmd(0x0010, 600);
  rig.cmd(kStartForward, 600, 100);
  EXPECT_GT(rig.outputFreq(), 0);
}

TEST(PowerFlex525, E26CommLossFaultsWithF083AndCoasts) {
  PowerFlexRig rig;
  rig.cmd(kStartForward, 1188, 1500);
  rig.silence(150);
  EXPECT_TRUE(rig.status() & 0x0080);
  EXPECT_FALSE(rig.status() & 0x0002);  // Active = 0
  EXPECT_EQ(rig.outputFreq(), 0);
  EXPECT_EQ(rig.drive->faultQueue()[0], 83);
  rig.cmd(0x0000, 1188, 2);
  rig.cmd(kClearFaults, 1188);          // cause gone once frames are back
  EXPECT_FALSE(rig.status() & 0x0080);
}

TEST(PowerFlex525, CommLossActionStopRampsWithoutFault) {
  PowerFlexParams p;
  p.commAction = CommLossAction::Stop;
  PowerFlexRig rig(TelegramId::Pf525, p);
  rig.cmd(kStartForward, 600, 1000);
  rig.silence(2000);
  EXPECT_FALSE(rig.status() & 0x0080);
  EXPECT_EQ(rig.outputFreq(), 0);
}

TEST(PowerFlex525, MopIncrementAndDecrementDriveTheNetworkReference) {
  PowerFlexParams p;
  p.mop = true;  // A430 = 10 s for P044 = 60 Hz: 6 Hz/s
  PowerFlexRig rig(TelegramId::Pf525, p);
  rig.cmd(kStartForward | 0x0080, 1188, 500);  // bit 7 MOPIncrement for 1 s (until the next frame)
  rig.cmd(kStartForward, 1188, 1000);          // released: the MOP holds; FreqCommand is unused
  EXPECT_NEAR(rig.drive->mopHz(), 6.0, 1e-6);
  EXPECT_EQ(rig.outputFreq(), 600);
  EXPECT_TRUE(rig.status() & 0x0100);          // AtReference on the MOP frequency
  rig.cmd(kStartForward | 0x8000, 1188, 250);  // bit 15 MOPDecrement for 0.5 s
  rig.cmd(kStartForward, 1188, 500);
  EXPECT_EQ(rig.outputFreq(), 300);
  rig.cmd(kStartForward | 0x4000, 1188, 1500);  // FreqSelect 100: preset A410 = 0 Hz wins
  EXPECT_EQ(rig.outputFreq(), 0);
  EXPECT_NEAR(rig.drive->mopHz(), 3.0, 1e-6);
}

// A429 = 1 (Preload): switching FreqSelect from a preset to the MOP continues from the output
// frequency; A428 = 0 (Zero MOP Ref): a Stop sets the MOP to 0.
TEST(PowerFlex525, MopPreloadsTheOutputFrequencyAndZeroesOnStop) {
  PowerFlexParams p;
  p.mop = true;
  p.mopPreload = true;
  p.mopSaveOnStop = false;
  PowerFlexRig rig(TelegramId::Pf525, p);
  rig.cmd(kStartForward | 0x6000, 0, 1500);  // FreqSelect 110: preset A412 = 10 Hz
  EXPECT_EQ(rig.outputFreq(), 1000);
  EXPECT_EQ(rig.drive->mopHz(), 0.0);
  rig.cmd(kStartForward, 0, 500);  // FreqSelect 000: the MOP, preloaded with 10 Hz
  EXPECT_NEAR(rig.drive->mopHz(), 10.0, 1e-9);
  EXPECT_EQ(rig.outputFreq(), 1000);
  rig.cmd(kStop, 0, 10);
  EXPECT_EQ(rig.drive->mopHz(), 0.0);
  p.mopPreload = false;  // the defaults: no preload, the MOP keeps its value over a Stop
  p.mopSaveOnStop = true;
  PowerFlexRig plain(TelegramId::Pf525, p);
  plain.cmd(kStartForward | 0x0080, 0, 500);  // MOPIncrement for 1 s: 6 Hz
  plain.cmd(kStartForward | 0x6000, 0, 1500);
  plain.cmd(kStartForward, 0, 10);
  EXPECT_NEAR(plain.drive->mopHz(), 6.0, 1e-9);
  plain.cmd(kStop, 0, 10);
  EXPECT_NEAR(plain.drive->mopHz(), 6.0, 1e-9);
}

TEST(PowerFlex525, MopBitsAreIgnoredUnlessConfigured) {
  PowerFlexRig rig;
  rig.cmd(kStartForward | 0x0080, 1188, 1500);
  EXPECT_EQ(rig.outputFreq(), 1188);
  EXPECT_EQ(rig.drive->mopHz(), 0.0);
}

TEST(PowerFlex525, FaultQueueKeepsTenMostRecentFirst) {
  PowerFlexRig rig;
  const uint16_t codes[] = {2, 3, 4, 5, 6, 7, 8, 9, 12, 13, 15};
  for (uint16_t c : codes) rig.drive->raiseFault(c, rig.nowNs);
  EXPECT_EQ(rig.drive->faultQueue()[0], 15);
  EXPECT_EQ(rig.drive->faultQueue()[9], 3);
}

TEST(PowerFlex750, RunsOnARealReferenceWith32BitWords) {
  PowerFlexRig rig(TelegramId::Pf750);
  rig.send({0x00000012, rawFromReal(30.0)}, 3000);
  EXPECT_DOUBLE_EQ(realValue(rig.tx(1)), 30.0);
  const uint32_t s = rig.tx(0);
  EXPECT_TRUE(s & (1u << 8));    // at speed
  EXPECT_TRUE(s & (1u << 16));   // running
  EXPECT_TRUE(s & (1u << 21));   // speed mode
  EXPECT_FALSE(s & (1u << 24));  // not at zero speed
  rig.send({0x00010000, rawFromReal(30.0)}, 1);  // coast stop
  EXPECT_EQ(realValue(rig.tx(1)), 0.0);
  EXPECT_FALSE(rig.tx(0) & (1u << 16));
}

TEST(PowerFlex750, PositionModeMovesTheEncoderToTheReferenceInDegrees) {
  PowerFlexParams p;
  p.positionMode = true;  // 60 Hz = 60 rev/s of the load (gear 1, one pole pair); 10 s accel/decel
  PowerFlexRig rig(TelegramId::Pf750, p);
  rig.send({0x00000012, rawFromReal(720.0)}, 1000);  // start: two revolutions, ~1.2 s triangle
  EXPECT_NEAR(realValue(rig.tx(1)), 720.0, 1e-6);    // Feedback = encoder degrees
  uint32_t s = rig.tx(0);
  EXPECT_TRUE(s & (1u << 8));    // at setpoint (in position)
  EXPECT_TRUE(s & (1u << 22));   // position mode
  EXPECT_FALSE(s & (1u << 21));  // not speed mode
  EXPECT_TRUE(s & (1u << 24));   // at zero speed
  rig.send({0x00000012, rawFromReal(-90.0)}, 1000);  // back past zero
  EXPECT_NEAR(realValue(rig.tx(1)), -90.0, 1e-6);
  rig.send({0x00000012, rawFromReal(36000.0)}, 250);  // far target, then a normal stop mid-move
  EXPECT_FALSE(rig.tx(0) & (1u << 24));
  rig.send({0x00000001, rawFromReal(36000.0)}, 1000);
  const double stopped = realValue(rig.tx(1));
  EXPECT_LT(stopped, 36000.0);
  EXPECT_GT(stopped, -90.0);
  s = rig.tx(0);
  EXPECT_FALSE(s & (1u << 8));   // stopped short of the reference
  EXPECT_TRUE(s & (1u << 24));
  rig.send({0x00000001, rawFromReal(36000.0)}, 250);
  EXPECT_EQ(realValue(rig.tx(1)), stopped);  // at rest where it stopped
}

TEST(PowerFlex750, PositionModeJogsAndTheEncoderFollowsACoastingMotor) {
  PowerFlexParams p;
  p.positionMode = true;
  PowerFlexRig rig(TelegramId::Pf750, p);
  rig.send({0x00000024, rawFromReal(0.0)}, 500);  // jog 1 reverse for 1 s: A431 = 10 Hz = 3600 deg/s
  EXPECT_LT(realValue(rig.tx(1)), 0.0);
  EXPECT_TRUE(rig.tx(0) & (1u << 17));            // jogging
  rig.send({0x00000001, rawFromReal(0.0)}, 1000); // released and stopped: brakes to rest
  const double jogged = realValue(rig.tx(1));
  rig.send({0x00000012, rawFromReal(36000.0)}, 500);
  rig.send({0x00010000, rawFromReal(36000.0)});   // coast stop: output off, the load runs on
  const double atCoast = realValue(rig.tx(1));
  EXPECT_GT(atCoast, jogged);
  rig.send({0x00010000, rawFromReal(36000.0)}, 250);
  EXPECT_GT(realValue(rig.tx(1)), atCoast);
  EXPECT_FALSE(rig.tx(0) & (1u << 16));           // not running
}

}  // namespace
}  // namespace virtcom::drives
