// EPos monitoring: following error F07452, positioning window F07451, standstill window
// F07450, sign-of-life F01912, setpoint timeout F01910 and acknowledge on the rising edge
// (docs/universal-axis.md, EPos position loop and monitoring; docs/drive-simulators.md, Faults
// and alarms), with raw telegram 111 words.
#include <gtest/gtest.h>

#include "epos_rig.hpp"

namespace virtcom::drives {
namespace {

// A slow position loop (tau_x = 300 ms) lags 1500 LU behind at 5000 LU/s: F07452, OFF3.
TEST(EposMonitoring, FollowingErrorTooHigh) {
  EposParams p;
  p.tauXS = 0.3;
  EposRig r(p);
  r.powerUp();
  r.cmd.stw1 = 0x063F;
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(3); }, 2000));
  EXPECT_EQ(r.faultCode(), 7452);
  EXPECT_FALSE(r.zsw1Bit(8)) << "ZSW1.8 following error out of tolerance";
  // Quick stop, then S1; acknowledged by a rising edge of STW1.7 (the cause was an event).
  r.cmd.stw1 = 0x043E;
  ASSERT_TRUE(r.runUntil([&] { return (r.zsw1() & 0x7F) == 0x78; }, 3000));
  r.cmd.stw1 = 0x04BE;
  r.sendCmd(2);
  EXPECT_FALSE(r.zsw1Bit(3));
  EXPECT_EQ(r.faultCode(), 0);
  EXPECT_EQ(r.drive->faultBuffer().entry(8).number, 7452) << "moved to the history";
}

// The setpoint is static but x_act does not reach p2544 within p2545: F07451.
TEST(EposMonitoring, PositioningWindowNotReached) {
  EposParams p;
  p.tauXS = 0.5;
  p.p2546 = 1e6;  // no following error fault
  p.p2545S = 0.3;
  EposRig r(p);
  r.powerUp();
  r.cmd.tarpos = 5000;
  r.cmd.velocity = 3000;
  r.cmd.posStw1 = 0x8000;
  r.activateTask();
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(3); }, 5000));
  EXPECT_EQ(r.faultCode(), 7451);
}

// At the target, an external force pushes the load out of the standstill window: F07450.
TEST(EposMonitoring, StandstillWindowLeft) {
  EposRig r;
  r.powerUp();
  r.cmd.tarpos = 2000;
  r.cmd.velocity = 600;
  r.cmd.posStw1 = 0x8000;
  r.activateTask();
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 5000));
  r.sendCmd(200);
  EXPECT_EQ(r.faultCode(), 0);
  r.drive->disturb(400);
  r.sendCmd();
  EXPECT_EQ(r.faultCode(), 7450);
  EXPECT_TRUE(r.zsw1Bit(3));
}

// E29: master counter 1,2,3,4,4,4 with p0925 = 1: F01912 at the second consecutive error;
// the slave counter runs 1..15 and never shows 0; 14,15,1,2 is valid.
TEST(EposMonitoring, SignOfLife) {
  EposParams p;
  p.solMonitor = true;
  EposRig r(p);
  r.powerUp();
  std::vector<int> slave;
  auto send = [&](uint16_t master) {
    r.cmd.stw2 = static_cast<uint16_t>(master << 12);
    r.sendCmd();
    slave.push_back(r.zsw2() >> 12);
  };
  for (uint16_t m : {14, 15, 1, 2, 3, 4}) send(m);
  EXPECT_EQ(r.faultCode(), 0);
  send(4);
  EXPECT_EQ(r.faultCode(), 0) << "first error tolerated (p0925 = 1)";
  send(4);
  EXPECT_EQ(r.faultCode(), 1912);
  for (int i = 0; i < 20; ++i) send(4);
  for (size_t i = 1; i < slave.size(); ++i) {
    EXPECT_NE(slave[i], 0);
    EXPECT_EQ(slave[i], slave[i - 1] % 15 + 1);
  }
}

// E26 for telegram 111: frames stop for 150 ms -> F01910 at >= 100 ms, OFF3, S1 (0x78).
TEST(EposMonitoring, SetpointTimeout) {
  EposRig r;
  r.powerUp();
  r.cmd.stw1 = 0x063F;
  r.sendCmd(100);
  r.silence(98);
  EXPECT_EQ(r.faultCode(), 0);
  r.silence(52);
  EXPECT_EQ(r.faultCode(), 1910);
  r.cmd.stw1 = 0x043F;
  ASSERT_TRUE(r.runUntil([&] { return (r.zsw1() & 0x7F) == 0x78; }, 2000));
  // Holding the acknowledge bit acts once; the drive stays in S1 while ON = 1.
  r.cmd.stw1 = 0x04BF;
  r.sendCmd(10);
  EXPECT_FALSE(r.zsw1Bit(3));
  EXPECT_EQ(r.zsw1() & 0x7F, 0x70);
  r.cmd.stw1 = 0x043E;
  r.sendCmd(2);
  EXPECT_EQ(r.zsw1() & 0x7F, 0x31) << "S2";
}

}  // namespace
}  // namespace virtcom::drives
