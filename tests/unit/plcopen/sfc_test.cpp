// The graphical SFC chart of beremiz_sfc.xml: a selective branch (abort has priority 0 over
// start), a simultaneous divergence/convergence, jumps back to Init, and action blocks
// (N referencing a POU action, P1 inline ST, S on a BOOL variable).
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

class ChartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    compiled_ = compileGolden("beremiz_sfc.xml");
    ASSERT_NE(compiled_->module, nullptr) << compiled_->rendered();
    plc_ = std::make_unique<Plc>(*compiled_->module);
  }
  std::string active() {
    std::string out;
    for (const char* step : {"Init", "Step2_1", "Step2_2", "Aborted"})
      if (plc_->get(std::string("CELL.") + step + ".X") == "TRUE") out += std::string(out.empty() ? "" : ",") + step;
    return out;
  }
  std::unique_ptr<Compiled> compiled_;
  std::unique_ptr<Plc> plc_;
};

TEST_F(ChartTest, ParallelBranchThenJumpBack) {
  plc_->scan();
  EXPECT_EQ(active(), "Init");
  plc_->set("CELL.start", "TRUE");
  plc_->scan();
  EXPECT_EQ(active(), "Step2_1,Step2_2");
  EXPECT_EQ(plc_->get("CELL.pulses"), "1");
  plc_->set("CELL.start", "FALSE");
  plc_->scan();
  EXPECT_EQ(active(), "Step2_1,Step2_2");
  EXPECT_EQ(plc_->get("CELL.pulses"), "1") << "P1 runs once per activation";
  EXPECT_EQ(plc_->get("CELL.fills"), "2") << "N runs every scan the step is active";
  plc_->set("CELL.done2", "TRUE");
  plc_->scan();
  EXPECT_EQ(active(), "Init") << "the transition after the convergence jumps back to Init";
}

TEST_F(ChartTest, SelectiveBranchPriorityAndStoredAction) {
  plc_->scan();
  plc_->set("CELL.start", "TRUE");
  plc_->set("CELL.abort", "TRUE");
  plc_->scan();
  EXPECT_EQ(active(), "Aborted") << "priority 0 (abort) wins over priority 1 (start)";
  EXPECT_EQ(plc_->get("CELL.alarm"), "TRUE");
  plc_->set("CELL.start", "FALSE");
  plc_->set("CELL.abort", "FALSE");
  plc_->set("CELL.reset", "TRUE");
  plc_->scan();
  EXPECT_EQ(active(), "Init");
  plc_->scan();
  EXPECT_EQ(plc_->get("CELL.alarm"), "TRUE") << "an S action stays set after its step ends";
}

}  // namespace
}  // namespace virtcom::plcopen::testing

namespace virtcom::plcopen::testing {
namespace {

// mixed_languages.xml (OpenPLC-editor style): an LD action driven by an SFC step, a transition
// whose condition is an FBD network assigning the transition's name, and a second ST body.
TEST(MixedLanguages, LdActionFbdTransitionAndSecondBody) {
  auto c = compileGolden("mixed_languages.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  plc.scan();
  EXPECT_EQ(plc.get("station.Idle.X"), "TRUE");
  plc.set("station.go", "TRUE");
  plc.scan();
  EXPECT_EQ(plc.get("station.Filling.X"), "TRUE");
  EXPECT_EQ(plc.get("station.lamp"), "TRUE") << "the LD action toggles the lamp";
  EXPECT_EQ(plc.get("station.level"), "1");
  plc.set("station.go", "FALSE");
  plc.scan();
  EXPECT_EQ(plc.get("station.lamp"), "FALSE");
  EXPECT_EQ(plc.get("station.level"), "2");
  plc.scan();
  EXPECT_EQ(plc.get("station.level"), "3");
  plc.scan();
  EXPECT_EQ(plc.get("station.Idle.X"), "TRUE") << "level >= 3 (FBD condition) leads back to Idle";
  EXPECT_EQ(plc.get("station.ticks"), "5") << "the second body runs every scan";
}

}  // namespace
}  // namespace virtcom::plcopen::testing
