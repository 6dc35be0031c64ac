// The ladder program of beremiz_ld.xml, run scan by scan (10 ms task).
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

class LadderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    compiled_ = compileGolden("beremiz_ld.xml");
    ASSERT_NE(compiled_->module, nullptr) << compiled_->rendered();
    plc_ = std::make_unique<Plc>(*compiled_->module);
  }
  std::unique_ptr<Compiled> compiled_;
  std::unique_ptr<Plc> plc_;
};

TEST_F(LadderTest, ParallelBranchSelfHoldAndNegatedContact) {
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.motor"), "FALSE");
  plc_->set("inst0.start", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.motor"), "TRUE");
  plc_->set("inst0.start", "FALSE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.motor"), "TRUE") << "the parallel motor contact holds the coil";
  plc_->set("inst0.stop", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.motor"), "FALSE");
  plc_->set("inst0.stop", "FALSE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.motor"), "FALSE");
}

TEST_F(LadderTest, RisingEdgeContactSeriesCoilsAndSetReset) {
  plc_->set("inst0.button", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.pulse"), "TRUE");
  EXPECT_EQ(plc_->get("inst0.latch"), "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.pulse"), "FALSE") << "one scan only while the button stays pressed";
  EXPECT_EQ(plc_->get("inst0.latch"), "TRUE") << "a set coil keeps its value";
  plc_->set("inst0.rst", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.latch"), "FALSE");
  plc_->set("inst0.rst", "FALSE");
  plc_->set("inst0.button", "FALSE");
  plc_->scan();
  plc_->set("inst0.button", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.pulse"), "TRUE") << "a second press is a second edge";
}

TEST_F(LadderTest, TimerBlockAndFallingEdgeCoil) {
  plc_->set("inst0.start", "TRUE");
  plc_->scan(3);  // motor on at 0, 10, 20 ms
  EXPECT_EQ(plc_->get("inst0.done"), "FALSE");
  plc_->scan();  // 30 ms
  EXPECT_EQ(plc_->get("inst0.done"), "TRUE");
  EXPECT_EQ(plc_->get("inst0.offPulse"), "FALSE");
  plc_->set("inst0.start", "FALSE");
  plc_->set("inst0.stop", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.offPulse"), "TRUE");
  EXPECT_EQ(plc_->get("inst0.done"), "FALSE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.offPulse"), "FALSE");
}

TEST_F(LadderTest, JumpSkipsRungsAndReturnEndsTheBody) {
  plc_->scan(3);
  EXPECT_EQ(plc_->get("inst0.count"), "3") << "ADD with EN from the rail counts every scan";
  plc_->set("inst0.skip", "TRUE");
  plc_->scan(2);
  EXPECT_EQ(plc_->get("inst0.count"), "3") << "the jump to AfterCount skips the counting rung";
  plc_->set("inst0.skip", "FALSE");
  plc_->set("inst0.zin", "TRUE");
  plc_->set("inst0.ret", "TRUE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.count"), "4");
  EXPECT_EQ(plc_->get("inst0.z"), "FALSE") << "RETURN comes before the last rung";
  plc_->set("inst0.ret", "FALSE");
  plc_->scan();
  EXPECT_EQ(plc_->get("inst0.z"), "TRUE");
}

}  // namespace
}  // namespace virtcom::plcopen::testing
