// EPos MDI positioning (relative, absolute), MDI setup, software limit switches, intermediate
// stop / reject and traversing blocks (docs/universal-axis.md, EPos modes), with raw telegram 111
// words.
#include <gtest/gtest.h>

#include "epos_rig.hpp"

namespace virtcom::drives {
namespace {

// Powered up and referenced at 0 (POS_STW2.1 edge).
EposRig referenced(EposParams p = {}) {
  EposRig r(p);
  r.powerUp();
  r.cmd.posStw2 = 0x0002;
  r.sendCmd(2);
  r.cmd.posStw2 = 0;
  r.sendCmd(2);
  return r;
}

// E13: absolute 70000 at MDI_VELOCITY 100 x OVERRIDE 50 %: ZSW1.12 toggles once, POS_ZSW2.4
// while moving, then XIST_A = 70000 +- p2544 and ZSW1 = 0x2F37 (ignoring the toggle bit 12).
TEST(EposMdi, AbsolutePositioningPositive) {
  EposRig r = referenced();
  r.cmd.tarpos = 70000;
  r.cmd.velocity = 100;
  r.cmd.override = 0x2000;
  r.cmd.posStw1 = 0x8300;
  r.sendCmd(5);
  const bool ack = r.zsw1Bit(12);
  r.activateTask();
  EXPECT_NE(r.zsw1Bit(12), ack) << "ZSW1.12 toggles on the accepted task";
  r.sendCmd(500);  // 1 s
  EXPECT_TRUE(r.posZsw2Bit(4));
  EXPECT_FALSE(r.zsw1Bit(10));
  EXPECT_TRUE(r.posZsw1Bit(15)) << "POS_ZSW1.15 MDI active";
  EXPECT_TRUE(r.posZsw2Bit(15)) << "POS_ZSW2.15 traversing command active";
  // 50 000 LU/min = 833 LU/s: about 84 s.
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 100000));
  EXPECT_NEAR(r.xist(), 70000, 40);
  EXPECT_GT(r.nowNs, 80'000'000'000) << "70 000 LU at 833 LU/s";
  r.sendCmd(100);
  EXPECT_EQ(r.xist(), 70000);
  EXPECT_EQ(r.zsw1() & ~0x1000, 0x2F37);
  EXPECT_NE(r.zsw1Bit(12), ack) << "toggled exactly once";
  EXPECT_TRUE(r.posZsw2Bit(2)) << "setpoint static";
}

// E14: a new target 10000 with POS_STW1 = 0x8500 moves backward; E2.6 same target: no motion.
TEST(EposMdi, AbsolutePositioningNegativeAndSameTarget) {
  EposRig r = referenced();
  r.cmd.tarpos = 20000;
  r.cmd.velocity = 1000;
  r.cmd.posStw1 = 0x8300;
  r.activateTask();
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 10000));
  r.cmd.tarpos = 10000;
  r.cmd.posStw1 = 0x8500;
  r.activateTask();
  r.sendCmd(100);
  EXPECT_TRUE(r.posZsw2Bit(5));
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 10000));
  r.sendCmd(50);
  EXPECT_EQ(r.xist(), 10000);
  // The same target again: ZSW1.10 never drops, the axis does not move.
  r.activateTask();
  for (int i = 0; i < 50; ++i) {
    r.sendCmd();
    ASSERT_TRUE(r.zsw1Bit(10));
  }
  EXPECT_EQ(r.xist(), 10000);
}

// E15: absolute positioning without a reference point: alarm A07461, no motion.
TEST(EposMdi, AbsoluteWithoutReferenceRaisesA07461) {
  EposRig r;
  r.powerUp();
  r.cmd.tarpos = 70000;
  r.cmd.posStw1 = 0x8300;
  r.activateTask();
  r.sendCmd(100);
  EXPECT_EQ(r.warnCode(), 7461);
  EXPECT_TRUE(r.zsw1Bit(7));
  EXPECT_EQ(r.xist(), 0);
  EXPECT_FALSE(r.posZsw2Bit(4));
}

// C.1 (thesis fig. 2.5): relative 3000, twice -> 6000; works without a reference point.
TEST(EposMdi, RelativePositioningAddsUp) {
  EposRig r;
  r.powerUp();
  r.cmd.tarpos = 3000;
  r.cmd.velocity = 600;
  r.cmd.posStw1 = 0x8000;
  r.activateTask();
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 5000));
  r.sendCmd(50);
  r.activateTask();
  r.sendCmd(10);
  EXPECT_FALSE(r.zsw1Bit(10));
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 5000));
  r.sendCmd(50);
  EXPECT_EQ(r.xist(), 6000);
}

// C.2: a new edge during the motion replaces the target on the fly.
TEST(EposMdi, TargetChangedOnTheFly) {
  EposRig r = referenced();
  r.cmd.tarpos = 50000;
  r.cmd.velocity = 3000;
  r.cmd.posStw1 = 0x8300;
  r.activateTask();
  r.sendCmd(100);
  ASSERT_GT(r.xist(), 1000);
  r.cmd.tarpos = 5000;
  r.activateTask();
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 10000));
  r.sendCmd(50);
  EXPECT_EQ(r.xist(), 5000);
}

// C.3: MDI setup moves at MDI_VELOCITY in the direction of POS_STW1.9/.10; neither stops;
// with POS_STW2.14 the axis stops at the software limit plus (POS_ZSW2.7, A07480).
TEST(EposMdi, SetupStopsAtSoftwareLimit) {
  EposParams p;
  p.p2581 = 5000;
  EposRig r(p);
  r.powerUp();
  r.cmd.velocity = 600;  // 10 000 LU/s
  r.cmd.posStw1 = 0xC200;
  r.activateTask();
  r.sendCmd(100);
  EXPECT_TRUE(r.posZsw1Bit(14)) << "POS_ZSW1.14 setup active";
  EXPECT_TRUE(r.posZsw2Bit(4));
  r.cmd.posStw1 = 0xC000;  // no direction: decelerate, task stays selected
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 1000));
  EXPECT_TRUE(r.posZsw1Bit(14));
  r.cmd.posStw2 = 0x4000;  // software limits on
  r.cmd.posStw1 = 0xC200;
  ASSERT_TRUE(r.runUntil([&] { return r.posZsw2Bit(7); }, 5000));
  r.sendCmd(100);
  EXPECT_EQ(r.xist(), 5000);
  EXPECT_EQ(r.warnCode(), 7480);
  EXPECT_FALSE(r.posZsw2Bit(6));
}

// C.10: STW1.5 = 0 pauses (task kept, resumes to the same target); STW1.4 = 0 discards it.
TEST(EposMdi, IntermediateStopAndReject) {
  EposRig r = referenced();
  r.cmd.tarpos = 30000;
  r.cmd.velocity = 1200;
  r.cmd.posStw1 = 0x8300;
  r.activateTask();
  r.sendCmd(200);
  r.cmd.stw1 = 0x041F;  // intermediate stop
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 2000));
  r.sendCmd(50);
  const int32_t paused = r.xist();
  r.sendCmd(100);
  EXPECT_EQ(r.xist(), paused);
  EXPECT_LT(paused, 30000);
  r.cmd.stw1 = 0x043F;
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(10); }, 10000));
  r.sendCmd(20);
  EXPECT_EQ(r.xist(), 30000);

  r.cmd.tarpos = 0;
  r.activateTask();
  r.sendCmd(200);
  r.cmd.stw1 = 0x042F;  // reject traversing task
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 2000));
  r.sendCmd(50);
  EXPECT_FALSE(r.posZsw2Bit(15)) << "task discarded";
  const int32_t stopped = r.xist();
  r.cmd.stw1 = 0x043F;
  r.sendCmd(200);
  EXPECT_EQ(r.xist(), stopped) << "a discarded task does not resume";
  EXPECT_GT(stopped, 0);
}

EposParams withBlocks() {
  using T = TraversingBlock;
  EposParams p;
  p.blocks = {
      {1, T::Task::PositionRel, T::Advance::ContinueWithStop, 2000, 600, 100, 100, 0},
      {2, T::Task::SetOutput, T::Advance::ContinueWithStop, 0, 100, 100, 100, 1},
      {3, T::Task::Wait, T::Advance::ContinueWithStop, 0, 100, 100, 100, 100},
      {4, T::Task::PositionRel, T::Advance::ContinueExternal, -1000, 600, 50, 50, 0},
      {5, T::Task::PositionAbs, T::Advance::End, 4000, 600, 100, 100, 0},
  };
  return p;
}

// C.7: blocks 1..5 run in order; block 4 waits for STW1.13 0 -> 1 before block 5.
TEST(EposBlocks, RunSequenceWithExternalChange) {
  EposRig r = referenced(withBlocks());
  r.cmd.posStw1 = 0x0001;  // block 1, MDI off
  r.activateTask();
  r.sendCmd(10);
  EXPECT_TRUE(r.posZsw1Bit(13)) << "POS_ZSW1.13 traversing blocks active";
  EXPECT_EQ(r.posZsw1() & 0x3F, 1);
  ASSERT_TRUE(r.runUntil([&] { return (r.posZsw1() & 0x3F) == 4 && r.zsw1Bit(10); }, 10000));
  EXPECT_TRUE(r.posZsw2Bit(10)) << "direct output 1 set by block 2";
  r.sendCmd(200);
  EXPECT_EQ(r.xist(), 1000) << "2000 then -1000; block 4 holds until the external change";
  EXPECT_EQ(r.posZsw1() & 0x3F, 4);
  r.cmd.stw1 |= 0x2000;
  r.sendCmd();
  ASSERT_TRUE(r.runUntil([&] { return !r.posZsw1Bit(13); }, 10000));
  r.sendCmd(50);
  EXPECT_EQ(r.xist(), 4000);
}

TEST(EposBlocks, UnknownBlockNumberRaisesAlarm) {
  EposRig r = referenced(withBlocks());
  r.cmd.posStw1 = 9;
  r.activateTask();
  r.sendCmd(50);
  EXPECT_EQ(r.warnCode(), 7462);
  EXPECT_FALSE(r.posZsw1Bit(13));
  EXPECT_EQ(r.xist(), 0);
  // A jog request while a block task runs is refused (C.8).
  r.cmd.posStw1 = 1;
  r.activateTask();
  r.cmd.stw1 |= 0x0200;
  r.sendCmd(50);
  EXPECT_FALSE(r.posZsw1Bit(10));
  EXPECT_TRUE(r.posZsw1Bit(13));
}

}  // namespace
}  // namespace virtcom::drives
