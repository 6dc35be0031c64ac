// The external PLC's link cut by a scenario (docs/scenarios.md "An external PLC and its link"):
// LinkLossBridge over a counting bridge, in both loss handlings, and the diagnostics of a `link`
// fault (the end-to-end runs against `virtcom exec --ads`: tests/e2e/ads_cell_e2e_test.cpp).
#include <gtest/gtest.h>

#include "scenario/link_loss.hpp"
#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

class CountingBridge final : public BusBridge {
 public:
  bool pull(TagBus&, int64_t) override { return ++pulls, true; }
  void push(const TagBus&, int64_t) override { ++pushes; }
  int pulls = 0, pushes = 0;
};

constexpr int64_t kMs = 1'000'000;

TEST(LinkLossBridge, HoldSkipsPollingDuringTheWindowOnly) {
  CountingBridge link;
  LinkLossBridge cut(link, {{20 * kMs, 30 * kMs}}, false);
  TagBus bus;
  for (int64_t t = 0; t < 100 * kMs; t += 10 * kMs) {
    EXPECT_TRUE(cut.pull(bus, t));
    cut.push(bus, t);
  }
  EXPECT_EQ(link.pulls, 7);  // 20, 30, 40 ms cut
  EXPECT_EQ(link.pushes, 7);
}

TEST(LinkLossBridge, FaultFailsTheFirstPullOfTheWindow) {
  CountingBridge link;
  LinkLossBridge cut(link, {{20 * kMs, 30 * kMs}}, true);
  TagBus bus;
  EXPECT_TRUE(cut.pull(bus, 10 * kMs));
  EXPECT_FALSE(cut.pull(bus, 20 * kMs));
  EXPECT_EQ(cut.failure(), "the link to the external PLC was lost (scenario comm_loss, on_loss: fault)");
  EXPECT_EQ(link.pulls, 1);
}

TEST_F(ScenarioTest, ALinkFaultNeedsAnExternalPlcAndWindows) {
  CaseResult r = run(R"(faults:
  - {link: plc, comm_loss: [{at: 1 s, duration: 1 s}]}
  - {link: drive, comm_loss: []}
)");
  ASSERT_EQ(r.verdict, Verdict::Error);
  const std::string t = text(r);
  EXPECT_NE(t.find("test.yaml:3:6: error[C063]: the cell's controller is its soft PLC"), std::string::npos) << t;
  EXPECT_NE(t.find("test.yaml:4:12: error[C063]: 'link' names the link to the cell's external PLC: 'plc'"), std::string::npos) << t;
  EXPECT_NE(t.find("test.yaml:4:30: error[C063]: 'comm_loss' lists windows"), std::string::npos) << t;
}

}  // namespace
}  // namespace virtcom::scenario::test
