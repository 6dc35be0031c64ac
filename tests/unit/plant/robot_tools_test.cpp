// Robot tools and workpiece facts: attach/detach at the magazine, grip/release, screw, and the
// error codes 21 (wrong/no tool), 22 (part missing), 50 (no stud).
#include <gtest/gtest.h>

#include "plant/robot.hpp"
#include "robot_fixture.hpp"

namespace virtcom::plant::test {
namespace {

class RobotTools : public ::testing::Test {
 protected:
  void SetUp() override {
    robot = static_cast<Robot*>(rig.add("robot", "R1", kRobotYaml));
    ASSERT_NE(robot, nullptr) << rig.renderedDiags();
    rig.prepare();
  }
  int run(int n) { return runProcedure(rig, "R1", n); }
  PlantRig rig;
  Robot* robot = nullptr;
};

TEST_F(RobotTools, AttachAtTheMagazineThenDetach) {
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 0);
  EXPECT_EQ(run(4), 0);  // move Magazine, attach Gripper1
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 1);
  EXPECT_EQ(robot->toolIndex(), 0);
  EXPECT_EQ(run(6), 0);
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 0);
}

TEST_F(RobotTools, AttachTakesToolChangeTimeAndTheToolShowsOnlyAtTheEnd) {
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(6), 0);
  rig.setNumber("R1.procedureNumber", 5);
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  rig.tick(999 * kMs);
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 0);
  rig.tick();
  EXPECT_EQ(rig.now - start, kS);
  EXPECT_TRUE(rig.getBool("R1.done"));
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 1);
}

TEST_F(RobotTools, AttachAwayFromTheMagazineIsError21) {
  EXPECT_EQ(run(5), 21);  // at Home, Gripper1 lives at Magazine
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 0);
}

TEST_F(RobotTools, AttachWhileAToolIsAttachedIsError21) {
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(9), 21);  // Screwer has no magazine, but Gripper1 is on
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 1);
}

TEST_F(RobotTools, DetachWithoutToolIsError21) { EXPECT_EQ(run(6), 21); }

TEST_F(RobotTools, DetachAwayFromTheMagazineIsError21) {
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(2), 0);  // home
  EXPECT_EQ(run(6), 21);
}

TEST_F(RobotTools, GripWithoutGripperIsError21) {
  rig.setFact("bearing1", true);
  EXPECT_EQ(run(7), 21);
  EXPECT_EQ(run(9), 0);  // screwer is no gripper
  EXPECT_EQ(run(7), 21);
  EXPECT_TRUE(rig.fact("bearing1"));
}

TEST_F(RobotTools, GripMissingPartIsError22) {
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(7), 22);
}

TEST_F(RobotTools, GripTakesThePartAndReleaseDropsIt) {
  EXPECT_EQ(run(4), 0);
  rig.setFact("bearing1", true);
  rig.setNumber("R1.procedureNumber", 7);
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  EXPECT_TRUE(rig.fact("bearing1"));  // taken at the end of close_time
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("R1.done"); }));
  EXPECT_EQ(rig.now - start, 200 * kMs);
  EXPECT_FALSE(rig.fact("bearing1"));
  EXPECT_DOUBLE_EQ(robot->payloadKg(), 1.8);
  rig.setBool("R1.execute", false);
  rig.tick();
  EXPECT_EQ(run(6), 21);  // cannot detach while holding a part
  int64_t at = 0;
  const int64_t placeStart = rig.now + kMs;
  EXPECT_EQ(runProcedure(rig, "R1", 8, &at), 0);
  EXPECT_EQ(at - placeStart, 100 * kMs);  // open_time
  EXPECT_TRUE(rig.fact("bearing1Placed"));
  EXPECT_DOUBLE_EQ(robot->payloadKg(), 1.0);
}

TEST_F(RobotTools, ReleaseWithoutThePartIsError22) {
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(8), 22);
  EXPECT_FALSE(rig.fact("bearing1Placed"));
}

TEST_F(RobotTools, ScrewWithoutStudIsError50) {
  EXPECT_EQ(run(9), 0);
  EXPECT_EQ(run(10), 50);
  EXPECT_FALSE(rig.fact("stud1Screwed"));
}

TEST_F(RobotTools, ScrewWithoutScrewerIsError21) {
  rig.setFact("stud1", true);
  EXPECT_EQ(run(10), 21);
  EXPECT_EQ(run(4), 0);
  EXPECT_EQ(run(10), 21);
}

TEST_F(RobotTools, ScrewTakesRundownTimeAndSetsScrewed) {
  EXPECT_EQ(run(9), 0);
  rig.setFact("stud1", true);
  const int64_t start = rig.now + kMs;
  int64_t at = 0;
  EXPECT_EQ(runProcedure(rig, "R1", 10, &at), 0);
  EXPECT_EQ(at - start, 1500 * kMs);
  EXPECT_TRUE(rig.fact("stud1Screwed"));
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 2);
}

TEST_F(RobotTools, SetAndClearFacts) {
  rig.setFact("flag", true);
  EXPECT_EQ(run(13), 0);
  EXPECT_FALSE(rig.fact("flag"));
}

TEST_F(RobotTools, FailureMidProcedureKeepsTheEffectsOfTheStepsBefore) {
  // AttachGripper from Far: moves to the magazine, then the attach fails because a tool is on.
  EXPECT_EQ(run(9), 0);
  rig.setNumber("R1.procedureNumber", 4);
  rig.setBool("R1.execute", true);
  rig.tick();
  const int64_t start = rig.now;
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getNumber("R1.error") != 0; }));
  EXPECT_EQ(rig.getNumber("R1.error"), 21);
  EXPECT_EQ(rig.now - start, 1500 * kMs);  // 500 mm move first
  EXPECT_FALSE(rig.getBool("R1.busy"));
  EXPECT_FALSE(rig.getBool("R1.done"));
  EXPECT_DOUBLE_EQ(rig.getNumber("R1.actualZ"), 400.0);
  const ActivityRecord& a = rig.trace.activities.back();
  EXPECT_EQ(a.errorCode, 21);
  EXPECT_GT(a.energyJ, 0.0);
}

// `initial_tool:` puts a tool on the flange before the first procedure (issue 16: robots
// started without a tool, so every cell needed an attach procedure first).
TEST(RobotInitialTool, StartsWithTheToolAttached) {
  PlantRig rig;
  auto* robot = static_cast<Robot*>(rig.add("robot", "R1", std::string(kRobotYaml) + "initial_tool: Gripper1\n"));
  ASSERT_NE(robot, nullptr) << rig.renderedDiags();
  rig.prepare();
  EXPECT_EQ(robot->toolIndex(), 0);
  EXPECT_DOUBLE_EQ(robot->payloadKg(), 1.0);  // the gripper's mass counts from the start
  rig.tick();
  EXPECT_EQ(rig.getNumber("R1.toolAttached"), 1);
  EXPECT_EQ(runProcedure(rig, "R1", 5), 21);  // attaching again: a tool is already on
}

TEST(RobotInitialTool, UnknownToolListsTheTools) {
  PlantRig rig;
  EXPECT_EQ(rig.add("robot", "R1", std::string(kRobotYaml) + "initial_tool: Gripper9\n"), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("R1.yaml:35:15: error[C010]: unknown tool 'Gripper9' (expected one of: Gripper1, Screwer)"),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace virtcom::plant::test
