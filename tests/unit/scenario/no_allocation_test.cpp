// A scenario's per-scan work allocates nothing (STYLE rule 7): with steps on the time line and on
// conditions, a force and its release, a button pressed twice (the second press while the first
// is held), and every per-tick assertion kind being judged, the station cell is stepped through
// several clamp cycles under a counted global operator new (tests/support/allocation_counter).
// The trace gets room for its records first.
#include <gtest/gtest.h>

#include "scenario/bind.hpp"
#include "scenario/checker.hpp"
#include "scenario/scenario_file.hpp"
#include "scenario/stimuli.hpp"
#include "scenario_fixture.hpp"
#include "support/allocation_counter.hpp"

namespace virtcom::scenario::test {
namespace {

TEST_F(ScenarioTest, StimuliAndAssertionsAllocateNothingPerTick) {
  const std::string path = write(R"(set: {MAIN.start: TRUE}
time_limit: 10 s
cycles: 100
steps:
  - {when: "MAIN.state = 2 AND MAIN.parts >= 2", set: {MAIN.cmd: 1}}
  - {at: 2 s, force: {MAIN.part: FALSE}}
  - {at: 3 s, release: MAIN.part}
  - {at: 3.5 s, facts: {partPresent: true}}
  - {at: 4 s, press: {MAIN.busy: 100 ms}}
  - {at: 4.05 s, press: {MAIN.busy: 200 ms}}
expect:
  - {always: NOT MAIN.failed}
  - {never: "MAIN.state = 9"}
  - {eventually: "MAIN.parts >= 4", within: 9 s}
  - {in_order: ["MAIN.parts = 1", "MAIN.parts = 2", "MAIN.parts = 3"]}
  - {plc_running: true}
  - {at: 8 s, that: "MAIN.parts > 3"}
)");
  SourceManager sources;
  Diagnostics diags;
  ScenarioFile file;
  ASSERT_TRUE(readScenarioFile(path, sources, diags, file)) << diags.render(sources);
  ConfigReader top(file.root, diags, "the scenario");
  auto cell = cell::loadCell(top.requireString("cell"), sources, diags);
  ASSERT_NE(cell, nullptr) << diags.render(sources);
  Plan plan = bindScenario(top, *cell, Controlled::Cell);
  ASSERT_FALSE(diags.hasErrors()) << diags.render(sources);
  Stimuli stimuli(plan, *cell);
  Checker checker(plan, *cell);
  sim::SimOptions options;
  options.preset = [&](plc::Runtime& plc) { stimuli.preset(plc); };
  options.beforeScan = [&](plc::Runtime& plc) { stimuli.beforeScan(plc); };
  options.traceSinks.push_back(&checker);
  sim::Simulation sim(*cell, options);
  checker.attach(&sim.plc());
  sim.trace().changes.reserve(1 << 20);
  sim.trace().activities.reserve(4096);
  // The window starts after the first cycle's record (an amortised append of the trace).
  while (sim.nowNs() < 1'100'000'000) ASSERT_TRUE(sim.step());
  const uint64_t ticksBefore = sim.ticks();
  {
    const virtcom::test::AllocationCounter allocations;
    while (sim.nowNs() < 9'000'000'000) ASSERT_TRUE(sim.step()) << "the run ended inside the window";
    EXPECT_EQ(allocations.count(), 0u);
  }
  EXPECT_GT(sim.ticks() - ticksBefore, 700u);  // 10 ms scans: steps on, no jumps
  sim.run();
  EXPECT_TRUE(checker.failures().empty()) << checker.failures().front().message;
}

}  // namespace
}  // namespace virtcom::scenario::test
