// The execute/done/error handshake of seed Figure 6 / Algorithm 3 as the robot implements it,
// tick by tick in 1 ms virtual time.
#include <gtest/gtest.h>

#include "plant/robot.hpp"
#include "robot_fixture.hpp"

namespace virtcom::plant::test {
namespace {

class RobotHandshake : public ::testing::Test {
 protected:
  void SetUp() override {
    robot = rig.add("robot", "R1", kRobotYaml);
    ASSERT_NE(robot, nullptr) << rig.renderedDiags();
    rig.prepare();
    rig.tick();  // t = 1 ms, idle
  }
  bool done() { return rig.getBool("R1.done"); }
  bool busy() { return rig.getBool("R1.busy"); }
  int error() { return static_cast<int>(rig.getNumber("R1.error")); }
  PlantRig rig;
  Device* robot = nullptr;
};

TEST_F(RobotHandshake, IdleUntilExecuteThenDoneAfterTheMoveAndDropsAfterExecuteDrops) {
  rig.setNumber("R1.procedureNumber", 1);  // GoFar: 1000 mm, 2.5 s
  for (int i = 0; i < 5; ++i) {
    rig.tick();
    EXPECT_FALSE(done());
    EXPECT_FALSE(busy());
  }
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  EXPECT_TRUE(busy());
  EXPECT_FALSE(done());
  ASSERT_TRUE(rig.tickUntil([&] { return done(); }));
  EXPECT_EQ(rig.now - start, 2500 * kMs);
  EXPECT_FALSE(busy());
  EXPECT_EQ(error(), 0);
  for (int i = 0; i < 10; ++i) {  // held while execute stays 1
    rig.tick();
    EXPECT_TRUE(done());
  }
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_FALSE(done());
  ASSERT_EQ(rig.trace.activities.size(), 1u);
  const ActivityRecord& a = rig.trace.activities[0];
  EXPECT_EQ(rig.label(a), "GoFar");
  EXPECT_EQ(a.startNs, start);
  EXPECT_EQ(a.endNs, start + 2500 * kMs);
  EXPECT_EQ(a.errorCode, 0);
}

TEST_F(RobotHandshake, UnknownProcedureRaisesError10WithoutDoneAndClearsWhenExecuteDrops) {
  rig.setNumber("R1.procedureNumber", 99);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_EQ(error(), 10);
  EXPECT_FALSE(done());
  EXPECT_FALSE(busy());
  for (int i = 0; i < 100; ++i) {
    rig.tick();
    EXPECT_EQ(error(), 10);
    EXPECT_FALSE(done());
  }
  EXPECT_EQ(robot->errorCode(), 10);
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_EQ(error(), 0);
  EXPECT_EQ(rig.getNumber("R1.actualX"), 0.0);  // nothing ran
  ASSERT_EQ(rig.trace.activities.size(), 1u);
  EXPECT_EQ(rig.label(rig.trace.activities[0]), "UnknownCommand");
  EXPECT_EQ(rig.trace.activities[0].errorCode, 10);
  EXPECT_EQ(rig.trace.activities[0].endNs, rig.trace.activities[0].startNs);
}

TEST_F(RobotHandshake, ExecuteDroppedMidProcedureRunsToTheEndThenDoneForOneTick) {
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  rig.tick(500 * kMs);
  rig.setBool("R1.execute", false);
  ASSERT_TRUE(rig.tickUntil([&] { return done(); }));
  EXPECT_EQ(rig.now - start, 2500 * kMs);  // the motion was not aborted
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 1000.0);
  rig.tick();
  EXPECT_FALSE(done());
  EXPECT_FALSE(busy());
  // back to idle: a new execute starts a new procedure
  rig.setNumber("R1.procedureNumber", 2);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_TRUE(busy());
}

TEST_F(RobotHandshake, NewExecuteOrNewNumberWhileBusyIsIgnored) {
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  rig.tick(100 * kMs);
  rig.setNumber("R1.procedureNumber", 3);
  rig.setBool("R1.execute", false);
  rig.tick();
  rig.setBool("R1.execute", true);
  ASSERT_TRUE(rig.tickUntil([&] { return done(); }));
  EXPECT_EQ(rig.now - start, 2500 * kMs);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 1000.0);  // still GoFar, not GoNear
  EXPECT_EQ(rig.trace.activities.size(), 1u);
  // execute is still 1 (re-raised while busy): done stays; nothing new starts
  for (int i = 0; i < 50; ++i) rig.tick();
  EXPECT_TRUE(done());
  EXPECT_EQ(rig.trace.activities.size(), 1u);
}

TEST_F(RobotHandshake, ExecuteHeldAfterDoneDoesNotRestart) {
  EXPECT_EQ(runProcedure(rig, "R1", 12), 0);  // Empty: done in the same tick
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  ASSERT_TRUE(rig.tickUntil([&] { return done(); }));
  for (int i = 0; i < 3000; ++i) rig.tick();
  EXPECT_EQ(rig.trace.activities.size(), 2u);
  EXPECT_FALSE(busy());
}

TEST_F(RobotHandshake, EmptyProcedureIsDoneAtTheTickExecuteIsSeen) {
  rig.setNumber("R1.procedureNumber", 12);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_TRUE(done());
  EXPECT_FALSE(busy());
}

TEST_F(RobotHandshake, PreconditionFailureStopsWithError20AndNoDone) {
  rig.setNumber("R1.procedureNumber", 11);  // require insertLocked
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_EQ(error(), 20);
  EXPECT_FALSE(done());
  EXPECT_FALSE(busy());
  EXPECT_FALSE(rig.fact("done1"));
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_EQ(error(), 0);
  rig.setFact("insertLocked", true);
  int64_t at = 0;
  const int64_t start = rig.now + kMs;
  EXPECT_EQ(runProcedure(rig, "R1", 11, &at), 0);
  EXPECT_EQ(at - start, 500 * kMs);
  EXPECT_TRUE(rig.fact("done1"));
  EXPECT_EQ(rig.trace.activities[0].errorCode, 20);
}

// A move's position output changes every tick (0: step the next one); the step's end is the
// event of steps that hold the outputs (a wait, a grip).
TEST_F(RobotHandshake, NextEventIsEveryTickWhileMovingThenWaitsForExecuteToDrop) {
  EXPECT_EQ(robot->nextEventNs(), INT64_MAX);
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_EQ(robot->nextEventNs(), 0);
  rig.tick(2500 * kMs);
  EXPECT_TRUE(done());
  EXPECT_EQ(robot->nextEventNs(), INT64_MAX);  // waits for execute to drop
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_EQ(robot->nextEventNs(), INT64_MAX);
}

TEST_F(RobotHandshake, AfterDoneWithExecuteAlreadyLowTheNextEventIsImmediate) {
  rig.setNumber("R1.procedureNumber", 12);
  rig.setBool("R1.execute", true);
  rig.tick();
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_FALSE(done());
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  rig.setBool("R1.execute", false);
  rig.tick(3 * kS);
  EXPECT_TRUE(done());
  EXPECT_LE(robot->nextEventNs(), rig.now);
}

TEST_F(RobotHandshake, InjectedErrorAtTheNthCommand) {
  robot->faults().errorCode = 90;
  robot->faults().errorAtCommand = 2;
  EXPECT_EQ(runProcedure(rig, "R1", 3), 0);
  EXPECT_EQ(runProcedure(rig, "R1", 1), 90);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 100.0);  // the faulty command did not move
  EXPECT_EQ(runProcedure(rig, "R1", 1), 0);
  EXPECT_EQ(rig.trace.activities[1].errorCode, 90);
  EXPECT_EQ(rig.label(rig.trace.activities[1]), "GoFar");
}

TEST_F(RobotHandshake, ErrorAtCommandZeroFailsEveryCommand) {
  robot->faults().errorCode = 90;
  EXPECT_EQ(runProcedure(rig, "R1", 3), 90);
  EXPECT_EQ(runProcedure(rig, "R1", 1), 90);
}

TEST_F(RobotHandshake, ExtraDelayPostponesDone) {
  robot->faults().extraDelayNs = 300 * kMs;
  const int64_t start = rig.now + kMs;
  int64_t at = 0;
  EXPECT_EQ(runProcedure(rig, "R1", 1, &at), 0);
  EXPECT_EQ(at - start, 2800 * kMs);
  EXPECT_EQ(rig.trace.activities[0].endNs - rig.trace.activities[0].startNs, 2800 * kMs);
}

TEST_F(RobotHandshake, DoneStuckNeverRaisesDoneButReturnsToIdleWhenExecuteDrops) {
  robot->faults().doneStuck = true;
  rig.setNumber("R1.procedureNumber", 1);
  rig.setBool("R1.execute", true);
  rig.tick();
  EXPECT_FALSE(rig.tickUntil([&] { return done(); }, 10 * kS));
  EXPECT_FALSE(busy());
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 1000.0);
  rig.setBool("R1.execute", false);  // the PLC times out
  rig.tick();
  robot->faults().doneStuck = false;
  EXPECT_EQ(runProcedure(rig, "R1", 2), 0);
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualX"), 0.0);
}

}  // namespace
}  // namespace virtcom::plant::test
