// EPos jog, incremental jog, set reference point, reference point approach and flying
// referencing (docs/universal-axis.md, EPos modes), with raw telegram 111 words.
#include <gtest/gtest.h>

#include "epos_rig.hpp"

namespace virtcom::drives {
namespace {

TEST(EposJog, PowerUpReachesOperationEnabled) {
  EposRig r;
  EXPECT_EQ(r.zsw1() & 0x7F, 0x70) << "S1 after power-up (OFF2/OFF3 inactive)";
  r.powerUp();
  EXPECT_EQ(r.zsw1() & 0x7F, 0x37) << "S4";
  EXPECT_TRUE((r.zsw2() >> 10) & 1) << "ZSW2.10 pulses enabled";
  EXPECT_TRUE((r.meldw() >> 13) & 1) << "MELDW.13 pulses enabled";
}

// E10: STW1 = 0x063F moves positive at p2586 = 300 000 LU/min (5000 LU/s).
TEST(EposJog, Jog2MovesPositiveAtP2586) {
  EposRig r;
  r.powerUp();
  r.cmd.stw1 = 0x063F;
  r.sendCmd(250);  // 500 ms
  EXPECT_TRUE(r.posZsw1Bit(10)) << "POS_ZSW1.10 jog active";
  EXPECT_TRUE(r.posZsw2Bit(4)) << "POS_ZSW2.4 moves forward";
  EXPECT_FALSE(r.zsw1Bit(7)) << "no alarm";
  // 5000 LU/s = 30 rpm at p2506 = 10000 LU/rev -> NIST_B = 30/1350 * 2^30.
  EXPECT_NEAR(r.nistB(), 30.0 / 1350.0 * 1073741824.0, 1e5);
  const int32_t x = r.xist();
  r.sendCmd(50);
  EXPECT_NEAR(r.xist() - x, 500, 2) << "100 ms at 5000 LU/s";
  // OVERRIDE 50 % halves the jog velocity.
  r.cmd.override = 0x2000;
  r.sendCmd(100);
  const int32_t x2 = r.xist();
  r.sendCmd(50);
  EXPECT_NEAR(r.xist() - x2, 250, 2);
  // Release: decelerate to standstill, jog no longer active.
  r.cmd.stw1 = 0x043F;
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 500));
  r.sendCmd(5);
  EXPECT_FALSE(r.posZsw1Bit(10));
  EXPECT_TRUE(r.zsw1Bit(13)) << "standstill";
}

// E11: STW1 = 0x053F (Jog1, p2585 negative) moves backward.
TEST(EposJog, Jog1MovesNegative) {
  EposRig r;
  r.powerUp();
  r.cmd.stw1 = 0x053F;
  r.sendCmd(100);
  EXPECT_TRUE(r.posZsw2Bit(5)) << "POS_ZSW2.5 moves backward";
  const int32_t x = r.xist();
  r.sendCmd(10);
  EXPECT_LT(r.xist(), x);
  EXPECT_LT(r.nistB(), 0);
  // Both jog bits: stop.
  r.cmd.stw1 = 0x073F;
  EXPECT_TRUE(r.runUntil([&] { return r.atRest(); }, 500));
}

// C.9: each 0 -> 1 of the jog bit moves p2588 (jog 2); holding does not repeat the move.
TEST(EposJog, IncrementalJogMovesOneStepPerEdge) {
  EposRig r;
  r.powerUp();
  r.cmd.posStw2 = 0x0020;  // POS_STW2.5 incremental
  r.cmd.stw1 = 0x063F;
  r.sendCmd(500);  // 1 s: arrive and hold
  EXPECT_NEAR(r.xist(), 1000, 1);
  EXPECT_TRUE(r.zsw1Bit(10)) << "ZSW1.10 at arrival";
  r.cmd.stw1 = 0x043F;
  r.sendCmd(5);
  r.cmd.stw1 = 0x063F;
  r.sendCmd(500);
  EXPECT_NEAR(r.xist(), 2000, 1);
  // Releasing before arrival stops the move short of the next step.
  r.cmd.stw1 = 0x043F;
  r.sendCmd(5);
  r.cmd.stw1 = 0x063F;
  r.sendCmd(50);  // 100 ms: on the way
  r.cmd.stw1 = 0x043F;
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 500));
  EXPECT_GT(r.xist(), 2000);
  EXPECT_LT(r.xist(), 3000);
}

// E12: POS_STW2.1 0 -> 1 at standstill sets XIST_A = p2599 = 0 and ZSW1.11.
TEST(EposReference, SetReferencePointAtStandstill) {
  EposRig r;
  r.powerUp();
  r.cmd.stw1 = 0x053F;
  r.sendCmd(200);
  r.cmd.stw1 = 0x043F;
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 500));
  r.sendCmd(20);
  ASSERT_LT(r.xist(), -1000);
  EXPECT_FALSE(r.zsw1Bit(11));
  r.cmd.posStw2 = 0x0002;
  r.sendCmd(2);
  EXPECT_EQ(r.xist(), 0);
  EXPECT_TRUE(r.zsw1Bit(11));
  // Held at 1 while jogging: nothing happens; a new edge while moving is ignored.
  r.cmd.stw1 = 0x063F;
  r.sendCmd(100);
  const int32_t moving = r.xist();
  EXPECT_GT(moving, 0);
  r.cmd.posStw2 = 0;
  r.sendCmd();
  r.cmd.posStw2 = 0x0002;
  r.sendCmd();
  EXPECT_GT(r.xist(), moving) << "edge while moving is ignored";
}

// E16: STW1 = 0x0C3F, POS_STW2 = 0: search in the positive direction, cam at 20000, zero mark
// every 10000; at the end XIST_A = p2599 = 0 and ZSW1.11 = 1.
TEST(EposReference, ReferenceApproachPositive) {
  EposRig r;
  r.powerUp();
  r.cmd.stw1 = 0x0C3F;
  r.sendCmd(50);
  EXPECT_TRUE(r.posZsw1Bit(11)) << "POS_ZSW1.11 reference point approach active";
  EXPECT_TRUE(r.posZsw2Bit(4)) << "moves positive";
  EXPECT_FALSE(r.zsw1Bit(11));
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(11); }, 20000));
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 2000));
  r.sendCmd(50);
  EXPECT_NEAR(r.xist(), 0, 40);
  EXPECT_FALSE(r.posZsw1Bit(11));
}

// E17: POS_STW2.9 = 1 searches negative (cam configured at -20000).
TEST(EposReference, ReferenceApproachNegativeAndAbort) {
  EposParams p;
  p.refCamPos = -20000;
  p.p2599 = 500;
  EposRig r(p);
  r.powerUp();
  r.cmd.posStw2 = 0x0200;
  r.cmd.stw1 = 0x0C3F;
  r.sendCmd(50);
  EXPECT_TRUE(r.posZsw2Bit(5)) << "POS_ZSW2.5 moves backward";
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(11); }, 20000));
  ASSERT_TRUE(r.runUntil([&] { return r.atRest(); }, 2000));
  r.sendCmd(50);
  EXPECT_NEAR(r.xist(), 500, 40) << "x := p2599";

  // STW1.11 = 0 before completion aborts: brake, not referenced.
  EposRig a(p);
  a.powerUp();
  a.cmd.posStw2 = 0x0200;
  a.cmd.stw1 = 0x0C3F;
  a.sendCmd(100);
  a.cmd.stw1 = 0x043F;
  ASSERT_TRUE(a.runUntil([&] { return a.atRest(); }, 3000));
  EXPECT_FALSE(a.zsw1Bit(11));
  EXPECT_FALSE(a.posZsw1Bit(11));
}

// C.4: without a cam the search starts at the zero mark; p2606 limits the cam search (F07458).
TEST(EposReference, CamSearchDistanceLimit) {
  EposParams p;
  p.p2606 = 5000;  // the cam at 20000 is out of reach
  EposRig r(p);
  r.powerUp();
  r.cmd.stw1 = 0x0C3F;
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(3); }, 5000));
  EXPECT_EQ(r.faultCode(), 7458);
  EXPECT_FALSE(r.zsw1Bit(11));

  EposParams noCam;
  noCam.hasRefCam = false;
  noCam.zeroMarkPos = 2500;
  EposRig n(noCam);
  n.powerUp();
  n.cmd.stw1 = 0x0C3F;
  ASSERT_TRUE(n.runUntil([&] { return n.zsw1Bit(11); }, 5000));
  ASSERT_TRUE(n.runUntil([&] { return n.atRest(); }, 2000));
  n.sendCmd(20);
  EXPECT_NEAR(n.xist(), 0, 40);
}

// C.5: STW1.11 with POS_STW2.8 arms the probe without moving; a jog across probe 1 (at 5000)
// sets x := p2599 + (x - x_probe).
TEST(EposReference, FlyingReferencing) {
  EposParams p;
  p.p2599 = 100000;
  EposRig r(p);
  r.powerUp();
  r.cmd.posStw2 = 0x0100;
  r.cmd.stw1 = 0x0C3F;
  r.sendCmd(20);
  EXPECT_TRUE(r.posZsw1Bit(12)) << "POS_ZSW1.12 flying referencing active";
  EXPECT_EQ(r.xist(), 0) << "no motion";
  r.cmd.stw1 = 0x0E3F;  // + jog 2
  ASSERT_TRUE(r.runUntil([&] { return r.zsw1Bit(11); }, 3000));
  EXPECT_FALSE(r.posZsw1Bit(12));
  // Crossed in the last bus cycle (2 ms at 5000 LU/s = 10 LU): x = p2599 + (x - 5000).
  EXPECT_GE(r.xist(), 100000);
  EXPECT_LE(r.xist(), 100000 + 11);
  const int32_t at = r.xist();
  r.sendCmd(100);
  EXPECT_NEAR(r.xist() - at, 1000, 20) << "the position keeps counting from the new reference";
}

}  // namespace
}  // namespace virtcom::drives
