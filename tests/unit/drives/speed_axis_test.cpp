// Siemens speed axis on telegram 1 / 352: acceptance scenarios of docs/drive-simulators.md seen
// from the drive, with raw words (p2000 = 1350 rpm).
#include <gtest/gtest.h>

#include <cmath>

#include "drive_rig.hpp"

namespace virtcom::drives {
namespace {

constexpr uint16_t kS1 = 0x70, kS2 = 0x31, kS3 = 0x33, kS4 = 0x37, kFaultInS1 = 0x78;

TEST(SpeedAxis, E1RunsAtHalfSpeedFromNsoll0x2000) {
  SpeedRig rig;
  EXPECT_EQ(rig.state(), kS1);  // power-up
  rig.stw(0x047E);
  EXPECT_EQ(rig.state(), kS2);
  rig.runAt(0x2000);
  EXPECT_EQ(rig.state(), kS4);
  EXPECT_NEAR(rig.nist(), 8192, 1);
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), 675.0, 0.1);
  EXPECT_TRUE(rig.zsw1() & (1u << 14));  // rotates forward
  EXPECT_TRUE(rig.zsw1() & (1u << 10));  // comparison speed reached
  EXPECT_TRUE(rig.zsw1() & (1u << 8));   // setpoint/actual within tolerance
  EXPECT_EQ(rig.zsw1(), 0xEF37);         // the typical running word of telegram 1
}

TEST(SpeedAxis, E2OverrideChangeTo75Percent) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.stw(0x047F, 12288, 1500);
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), 1012.5, 0.1);
  EXPECT_NEAR(rig.nist(), 12288, 1);
}

TEST(SpeedAxis, E3SetpointInversionRunsBackwards) {
  SpeedRig rig;
  rig.runAt(0x2000, 0x0C7F);
  EXPECT_NEAR(rig.nist(), -8192, 1);  // 0xE000
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), -675.0, 0.1);
  EXPECT_FALSE(rig.zsw1() & (1u << 14));
  EXPECT_EQ(rig.state(), kS4);
}

TEST(SpeedAxis, E4E5JogAtTwentyPercent) {
  SpeedRig fwd;
  fwd.runAt(3277);
  EXPECT_NEAR(fwd.drive->shaftSpeedRpm(), 270.02, 0.01);
  SpeedRig rev;
  rev.runAt(3277, 0x0C7F);
  EXPECT_NEAR(rev.drive->shaftSpeedRpm(), -270.02, 0.01);
}

TEST(SpeedAxis, RampUpFollowsP1120) {
  SpeedRig rig;  // p1120 = 2 s for p1082 = 1350 rpm: 675 rpm take 1 s
  rig.stw(0x047E);
  rig.stw(0x047F, 0x2000, 250);  // 0.5 s
  EXPECT_NEAR(rig.drive->rfgOutputRpm(), 337.5, 2.0);
  EXPECT_TRUE(rig.zsw1() & (1u << 14));
}

// A scenario's `parameter:` step (docs/scenarios.md): p1120 from 2 s to 1 s in the middle of
// the ramp-up; the ramp goes on from where it is at the new slope. The scaling p2000 stays.
TEST(SpeedAxis, RampTimeChangesMidRamp) {
  SpeedRig rig;  // 675 rpm/s up to 0.5 s (337.5 rpm), then 1350 rpm/s
  SpeedAxisParams faster;
  faster.p1120S = 1.0;
  SpeedRig edited(TelegramId::Std1, faster);
  EXPECT_TRUE(rig.drive->changesParameter("p1120"));
  EXPECT_FALSE(rig.drive->changesParameter("p2000"));
  EXPECT_FALSE(rig.drive->changesParameter("telegram"));
  rig.stw(0x047E);
  rig.stw(0x047F, 0x2000, 250);  // 0.5 s
  EXPECT_NEAR(rig.drive->rfgOutputRpm(), 337.5, 2.0);
  rig.drive->swapParameters(*edited.drive);
  rig.stw(0x047F, 0x2000, 100);  // 0.2 s more: 270 rpm more
  EXPECT_NEAR(rig.drive->rfgOutputRpm(), 607.5, 2.0);
}

TEST(SpeedAxis, RfgFreezeAndDisable) {
  SpeedRig rig;
  rig.stw(0x047E);
  rig.stw(0x047F, 0x2000, 250);
  rig.stw(0x045F, 0x2000);        // bit 5 = 0: freeze (acts from the next interval)
  const double frozen = rig.drive->rfgOutputRpm();
  rig.stw(0x045F, 0x2000, 100);
  EXPECT_DOUBLE_EQ(rig.drive->rfgOutputRpm(), frozen);
  rig.stw(0x043F, 0x2000, 100);  // bit 6 = 0: setpoint 0, ramps down with p1121
  EXPECT_LT(rig.drive->rfgOutputRpm(), frozen);
  rig.stw(0x046F, 0x2000, 1000);  // bit 4 = 0: RFG output to 0 along the OFF3 slope
  EXPECT_EQ(rig.drive->rfgOutputRpm(), 0.0);
  EXPECT_EQ(rig.state(), kS4);     // still operation enabled
}

TEST(SpeedAxis, T352SpeedCurrentTorqueAndCodes) {  // E6, E7
  SpeedRig rig(TelegramId::Siemens352);
  rig.stw352(0x047E, 0, 2);
  rig.stw352(0x047F, 13107, 1500);
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), 1079.98, 0.01);
  EXPECT_NEAR(static_cast<int16_t>(rig.tx(1)), 13107, 1);  // NIST_A_GLATT
  EXPECT_GT(static_cast<int16_t>(rig.tx(2)), 0);           // IAIST_GLATT: magnetising current
  EXPECT_EQ(rig.tx(4), 0u);                                // WARN_CODE
  EXPECT_EQ(rig.tx(5), 0u);                                // FAULT_CODE
  SpeedRig rev(TelegramId::Siemens352);
  rev.stw352(0x047E, 0, 2);
  rev.stw352(0x0C7F, 13107, 1500);
  EXPECT_NEAR(static_cast<int16_t>(rev.tx(1)), -13107, 1);
}

TEST(SpeedAxis, T352TorqueFollowsTheLoad) {
  DriveCommon c;
  c.telegram = TelegramId::Siemens352;
  c.load.loadTorqueNm = 5.0;  // half of p2003 = 10 Nm
  SpeedRig rig(TelegramId::Siemens352);
  rig.drive = std::make_unique<SpeedAxis>("G120", c, SpeedAxisParams{});
  rig.stw352(0x047E, 0, 2);
  rig.stw352(0x047F, 0x2000, 1500);
  EXPECT_NEAR(static_cast<int16_t>(rig.tx(3)), 8192, 2);  // MIST_GLATT = 50 % of p2003
}

TEST(SpeedAxis, E30StateMachineFromRawWords) {
  SpeedRig rig;
  rig.stw(0x047F, 0, 5);
  EXPECT_EQ(rig.state(), kS1);  // needs OFF1 = 0 first
  rig.stw(0x047E);
  EXPECT_EQ(rig.state(), kS2);
  rig.stw(0x047F, 0x2000);
  EXPECT_EQ(rig.state(), kS4);  // S2 -> S3 -> S4 in one frame
  rig.stw(0x047F, 0x2000, 1000);
  rig.stw(0x047D, 0x2000);      // OFF2: S1 at once, the motor coasts
  EXPECT_EQ(rig.state() & 0x47, 0x40);
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 600.0);
  rig.stw(0x047D, 0x2000, 50);
  EXPECT_LT(rig.drive->shaftSpeedRpm(), 675.0);
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 0.0);
}

// With the pulses off the load's friction torque brakes the shaft too (issue 16: the coast
// ignored it, so a loaded axis ran on for seconds). 0.5 Nm on 0.002 kgm^2 is 250 rad/s^2, about
// 2400 rpm/s: from 675 rpm the shaft stands within 0.3 s; without a load torque it still turns.
TEST(SpeedAxis, CoastingIsBrakedByTheLoadTorque) {
  DriveCommon loaded;
  loaded.load.inertiaKgm2 = 0.002;
  loaded.load.loadTorqueNm = 0.5;
  SpeedRig rig;
  rig.drive = std::make_unique<SpeedAxis>("G120", loaded, SpeedAxisParams{});
  rig.drive->exchange({}, rig.nowNs);
  rig.runAt(0x2000);
  ASSERT_NEAR(rig.drive->shaftSpeedRpm(), 675.0, 2.0);
  rig.sendFor({0x047D, 0x2000}, 150);  // OFF2: pulses off at once
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 100.0) << "still braking";
  EXPECT_LT(rig.drive->shaftSpeedRpm(), 675.0 * std::exp(-0.15 / 2.0) - 300.0) << "faster than the run-down alone";
  rig.sendFor({0x047D, 0x2000}, 200);
  EXPECT_EQ(rig.drive->shaftSpeedRpm(), 0.0) << "stands, and never turns back";

  SpeedRig idle;
  idle.drive = std::make_unique<SpeedAxis>("G120", DriveCommon{}, SpeedAxisParams{});
  idle.drive->exchange({}, idle.nowNs);
  idle.runAt(0x2000);
  idle.sendFor({0x047D, 0x2000}, 350);
  EXPECT_NEAR(idle.drive->shaftSpeedRpm(), 675.0 * std::exp(-0.35 / 2.0), 15.0) << "tau_coast alone";
}

TEST(SpeedAxis, E30InhibitOperationGoesToS3AndBack) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.stw(0x0477, 0x2000);  // bit 3 = 0
  EXPECT_EQ(rig.state(), kS3);
  rig.stw(0x047F, 0x2000);
  EXPECT_EQ(rig.state(), kS4);
}

TEST(SpeedAxis, E30Off3RampsWithP1135ThenS1) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.stw(0x047B, 0x2000, 100);  // 0.2 s of a 0.25 s quick stop from 675 rpm
  EXPECT_EQ(rig.state() & 0x27, 0x05);  // S5b: bits 0, 2, bit 5 = 0
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 0.0);
  rig.stw(0x047B, 0x2000, 100);
  EXPECT_EQ(rig.state() & 0x47, 0x40);  // S1
  EXPECT_LT(rig.drive->shaftSpeedRpm(), 20.0);
}

TEST(SpeedAxis, Off1RampsWithP1121ThenS2) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.stw(0x047E, 0x2000, 250);  // 0.5 s of a 1 s ramp-down
  EXPECT_EQ(rig.state(), 0x35);  // S5a
  EXPECT_NEAR(rig.drive->shaftSpeedRpm(), 337.5, 20.0);
  rig.stw(0x047E, 0x2000, 400);
  EXPECT_EQ(rig.state(), kS2);
  rig.stw(0x047F, 0x2000);
  EXPECT_EQ(rig.state(), kS4);
}

// ZSW1.8 (SINAMICS r2199.4): set as soon as |n_set - n_act| <= p2163; dropped only once the
// deviation has stayed beyond p2163 + p2164 for the off delay p2166.
TEST(SpeedAxis, Zsw1Bit8DropsP2166AfterTheDeviationLeavesTheTolerance) {
  SpeedAxisParams p;
  p.p2163 = 5;  // below the ramp's tracking lag (675 rpm/s x 20 ms = 13.5 rpm)
  SpeedRig rig(TelegramId::Std1, p);
  rig.stw(0x047E, 0, 2);
  EXPECT_TRUE(rig.zsw1() & (1u << 8)) << "at rest the actual speed is the setpoint";
  rig.stw(0x047F, 0x2000, 50);   // 100 ms into the 1 s ramp: out of tolerance for less than p2166 = 200 ms
  EXPECT_TRUE(rig.zsw1() & (1u << 8));
  rig.stw(0x047F, 0x2000, 100);  // 300 ms: out for longer than p2166
  EXPECT_FALSE(rig.zsw1() & (1u << 8));
  rig.stw(0x047F, 0x2000, 500);  // the ramp has ended and the lag decayed into p2163: set at once
  EXPECT_TRUE(rig.zsw1() & (1u << 8));
  EXPECT_EQ(rig.zsw1(), 0xEF37);
  p.p2166S = 0;  // no off delay: the bit drops with the deviation
  SpeedRig direct(TelegramId::Std1, p);
  direct.stw(0x047E, 0, 2);
  direct.stw(0x047F, 0x2000, 50);
  EXPECT_FALSE(direct.zsw1() & (1u << 8));
}

// A deviation between p2163 and p2163 + p2164 keeps ZSW1.8 as it is.
TEST(SpeedAxis, Zsw1Bit8HysteresisP2164HoldsTheBitAboveP2163) {
  SpeedAxisParams p;
  p.p2163 = 10;
  p.p2164 = 5;  // the ramp's tracking lag, 13.5 rpm, lies between p2163 and p2163 + p2164
  p.p2166S = 0;
  SpeedRig held(TelegramId::Std1, p);
  held.stw(0x047E, 0, 2);
  held.stw(0x047F, 0x2000, 250);
  EXPECT_TRUE(held.zsw1() & (1u << 8));
  p.p2164 = 2;
  SpeedRig dropped(TelegramId::Std1, p);
  dropped.stw(0x047E, 0, 2);
  dropped.stw(0x047F, 0x2000, 250);
  EXPECT_FALSE(dropped.zsw1() & (1u << 8));
  dropped.stw(0x047F, 0x2000, 500);  // after the ramp the lag falls back below p2163
  EXPECT_TRUE(dropped.zsw1() & (1u << 8));
}

TEST(SpeedAxis, Off1EndsOnSetpointStandstillP1227WhileTheMotorStillTurns) {
  SpeedAxisParams p;
  p.tauSpeedS = 10;  // a motor that lags far behind its setpoint (e.g. a driving load)
  p.p1227S = 1;
  SpeedRig rig(TelegramId::Std1, p);
  rig.stw(0x047E, 0, 2);
  rig.stw(0x047F, 0x2000, 1500);
  rig.stw(0x047E, 0x2000, 750);  // OFF1: RFG output 0 after 1 s, p1227 not yet elapsed
  EXPECT_EQ(rig.state(), 0x35);  // S5a
  EXPECT_EQ(rig.drive->rfgOutputRpm(), 0.0);
  rig.stw(0x047E, 0x2000, 350);
  EXPECT_EQ(rig.state(), kS2);   // pulses off although |n_act| > p1226
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 20.0);
  p.p1227S = 300;                // the default: only the actual speed ends the ramp
  SpeedRig slow(TelegramId::Std1, p);
  slow.stw(0x047E, 0, 2);
  slow.stw(0x047F, 0x2000, 1500);
  slow.stw(0x047E, 0x2000, 1100);
  EXPECT_EQ(slow.state(), 0x35);
}

TEST(SpeedAxis, MopRaiseAndLowerIntegrateTheMainSetpoint) {
  SpeedAxisParams p;
  p.mop = true;  // p1047 = 10 s for p1082 = 1350 rpm: 135 rpm/s
  SpeedRig rig(TelegramId::Std1, p);
  rig.stw(0x047E, 0x2000, 2);
  rig.stw(0x247F, 0x2000, 500);   // STW1.13 raise for 1 s (until the next frame); NSOLL_A is not the setpoint
  rig.stw(0x047F, 0x2000, 750);   // released: the MOP holds
  EXPECT_NEAR(rig.drive->mopRpm(), 135.0, 1e-6);
  EXPECT_EQ(rig.nist(), 1638);    // 135 rpm x 16384 / 1350
  rig.stw(0x647F, 0x2000, 250);   // raise and lower together hold
  EXPECT_NEAR(rig.drive->mopRpm(), 135.0, 1e-6);
  rig.stw(0x447F, 0x2000, 250);   // STW1.14 lower for 0.5 s
  rig.stw(0x0C7F, 0x2000, 750);   // inverted like any setpoint
  EXPECT_EQ(rig.nist(), -819);
  rig.stw(0x447F, 0x2000, 1000);  // lowers to 0, not below
  EXPECT_EQ(rig.drive->mopRpm(), 0.0);
}

// p1040 is the MOP setpoint at power-up and at every ON; with p1030.0 (data save) the MOP keeps
// its setpoint from one ON to the next instead.
TEST(SpeedAxis, MopStartsFromP1040AtEveryOnUnlessP1030StoresIt) {
  for (const bool store : {false, true}) {
    SpeedAxisParams p;
    p.mop = true;  // 135 rpm/s
    p.p1040 = 270;
    p.p1030Store = store;
    SpeedRig rig(TelegramId::Std1, p);
    EXPECT_EQ(rig.drive->mopRpm(), 270.0);
    rig.stw(0x047E, 0, 2);
    rig.stw(0x247F, 0, 500);  // raise for 1 s
    rig.stw(0x047F, 0, 1);
    EXPECT_NEAR(rig.drive->mopRpm(), 405.0, 1e-6);
    rig.stw(0x047E, 0, 1000);  // OFF1 down to S2
    EXPECT_EQ(rig.state(), kS2);
    rig.stw(0x047F, 0, 2);  // ON again
    EXPECT_EQ(rig.state(), kS4);
    EXPECT_NEAR(rig.drive->mopRpm(), store ? 405.0 : 270.0, 1e-6) << "p1030 = " << store;
  }
}

TEST(SpeedAxis, MopBitsAreIgnoredUnlessConfigured) {
  SpeedRig rig;
  rig.runAt(0x2000, 0x247F);
  EXPECT_NEAR(rig.nist(), 8192, 1);
  EXPECT_EQ(rig.drive->mopRpm(), 0.0);
}

TEST(SpeedAxis, E30FrameWithoutControlByPlcIsIgnored) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.stw(0x007E, 0x4000, 500);  // OFF1 and a new setpoint, but bit 10 = 0
  EXPECT_EQ(rig.state(), kS4);
  EXPECT_NEAR(rig.nist(), 8192, 1);
}

TEST(SpeedAxis, E26SetpointTimeoutRaisesF01910AndStopsWithOff3) {
  SpeedRig rig(TelegramId::Siemens352);
  rig.stw352(0x047E, 0, 2);
  rig.stw352(0x047F, 0x2000, 1500);
  rig.silence(98);
  EXPECT_EQ(rig.tx(0) & 0x08, 0u);   // not yet at 98 ms
  rig.silence(52);                   // 150 ms without frames
  EXPECT_TRUE(rig.tx(0) & 0x08);     // ZSW1.3
  EXPECT_EQ(rig.tx(5), 1910u);       // FAULT_CODE
  EXPECT_EQ(rig.drive->faultBuffer().entry(0).number, 1910);
  rig.stw352(0x047F, 0x2000, 200);   // frames resume, ON still 1
  EXPECT_EQ(rig.state(), kFaultInS1);
  EXPECT_LT(std::abs(rig.drive->shaftSpeedRpm()), 20.0);
}

TEST(SpeedAxis, E26ProfinetProfileRaisesF08501) {
  SpeedAxisParams p;
  p.commFault = 8501;
  SpeedRig rig(TelegramId::Siemens352, p);
  rig.stw352(0x047E, 0, 2);
  rig.silence(150);
  EXPECT_EQ(rig.tx(5), 8501u);
}

TEST(SpeedAxis, CommLossBeforeControlByPlcIsOnlyAlarmA01920) {
  SpeedRig rig(TelegramId::Siemens352);
  rig.silence(150);
  EXPECT_EQ(rig.tx(4), 1920u);        // WARN_CODE
  EXPECT_TRUE(rig.tx(0) & 0x80);      // ZSW1.7
  EXPECT_FALSE(rig.tx(0) & 0x08);
  rig.stw352(0x047E, 0, 1);
  EXPECT_EQ(rig.tx(4), 0u);           // cause gone, no acknowledge needed
  EXPECT_EQ(rig.state(), kS2);
}

TEST(SpeedAxis, E27AcknowledgeOnRisingEdgeOnly) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.silence(150);
  rig.stw(0x047F, 0x2000, 200);
  ASSERT_EQ(rig.state(), kFaultInS1);
  rig.stw(0x04FF, 0x2000, 1);        // ack edge
  EXPECT_EQ(rig.zsw1() & 0x08, 0u);
  EXPECT_TRUE(rig.zsw1() & 0x40);     // stays S1: ON is still 1
  rig.stw(0x04FF, 0x2000, 9);
  rig.stw(0x04FE, 0x2000);            // ON = 0 -> S2
  EXPECT_EQ(rig.state(), kS2);
  rig.stw(0x04FF, 0x2000);            // ON -> S4 (ack bit still held)
  EXPECT_EQ(rig.state(), kS4);
  rig.drive->raiseFault(7900, Reaction::Off2, rig.nowNs);  // a second fault, cause gone at once
  rig.drive->removeFaultCause(7900);
  rig.stw(0x04FF, 0x2000, 10);        // ack held at 1: not acknowledged
  EXPECT_TRUE(rig.zsw1() & 0x08);
  rig.stw(0x047F, 0x2000);            // 1 -> 0
  rig.stw(0x04FF, 0x2000);            // 0 -> 1
  EXPECT_EQ(rig.zsw1() & 0x08, 0u);
}

TEST(SpeedAxis, FaultWhoseCausePersistsSurvivesAcknowledge) {
  SpeedRig rig;
  rig.stw(0x047E);
  rig.drive->raiseFault(30001, Reaction::Off2, rig.nowNs);
  rig.stw(0x04FE);
  EXPECT_TRUE(rig.zsw1() & 0x08);
  rig.drive->removeFaultCause(30001);
  rig.stw(0x047E);
  rig.stw(0x04FE);
  EXPECT_EQ(rig.zsw1() & 0x08, 0u);
  EXPECT_EQ(rig.state(), kS2);  // ON = 0: straight on to S2
}

TEST(SpeedAxis, E28FaultBufferKeepsEightAndOverwritesIndexSeven) {
  SpeedRig rig;
  const uint16_t codes[] = {1000, 1001, 1015, 1105, 1250, 7900, 30001, 30002, 30003};
  for (uint16_t c : codes) {
    rig.drive->raiseFault(c, Reaction::Off2, rig.nowNs);
    rig.stw(0x047E);
  }
  const FaultBuffer& b = rig.drive->faultBuffer();
  EXPECT_EQ(b.activeCount(), 8u);
  for (size_t i = 0; i < 7; ++i) EXPECT_EQ(b.entry(i).number, codes[i]);
  EXPECT_EQ(b.entry(7).number, 30003);
  for (uint16_t c : codes) rig.drive->removeFaultCause(c);
  rig.stw(0x04FE);
  EXPECT_EQ(b.activeCount(), 0u);
  EXPECT_EQ(b.entry(0).number, 0);
  EXPECT_EQ(b.entry(8).number, 1000);
  EXPECT_EQ(b.entry(15).number, 30003);
  EXPECT_GE(b.entry(8).removedNs, b.entry(8).raisedNs);
}

TEST(SpeedAxis, E28AlarmBufferAndAlarmsClearWithoutAcknowledge) {
  SpeedRig rig(TelegramId::Siemens352);
  const uint16_t codes[] = {1028, 1920, 3520, 5000, 5001, 5002, 5003, 5004, 5005};
  for (uint16_t c : codes) {
    rig.drive->raiseAlarm(c, rig.nowNs);
    rig.stw352(0x047E, 0);
  }
  const AlarmBuffer& a = rig.drive->alarmBuffer();
  EXPECT_EQ(a.activeCount(), 8u);
  EXPECT_EQ(a.entry(6).number, 5003);
  EXPECT_EQ(a.entry(7).number, 5005);
  EXPECT_EQ(rig.tx(4), 5005u);              // WARN_CODE = most recent active
  EXPECT_FALSE(rig.tx(0) & (1u << 15));     // power unit over-temperature
  EXPECT_FALSE(rig.tx(0) & (1u << 13));     // A03520: motor temperature
  for (uint16_t c : codes) rig.drive->clearAlarm(c, rig.nowNs);
  rig.stw352(0x047E, 0);
  EXPECT_FALSE(rig.tx(0) & 0x80);
  EXPECT_EQ(rig.tx(4), 0u);
  EXPECT_EQ(a.entry(8).number, 5005);       // most recently cleared first
}

TEST(SpeedAxis, Off3FaultReactionRampsThenS1) {
  SpeedRig rig;
  rig.runAt(0x2000);
  rig.drive->raiseFault(7452, Reaction::Off3, rig.nowNs);
  rig.stw(0x047F, 0x2000, 20);
  EXPECT_TRUE(rig.zsw1() & 0x08);
  EXPECT_GT(rig.drive->shaftSpeedRpm(), 100.0);  // still ramping along p1135
  rig.stw(0x047F, 0x2000, 200);
  EXPECT_EQ(rig.state(), kFaultInS1);
}

}  // namespace
}  // namespace virtcom::drives
