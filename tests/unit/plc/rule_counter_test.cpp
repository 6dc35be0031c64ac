// plc::RuleCounter, the one counter of activity-diagram rule firings (the reports' rule tables and
// the HMI's rule panel): a rule counts in the scans of its own task only, at the tick's time, and
// starts again at 0 on a fresh runtime.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "plc/rule_counter.hpp"

namespace virtcom::plc {
namespace {

constexpr int64_t kMs = 1'000'000;

// `always` holds in every scan of its task; `odd` in every second one.
const char* const kFlags = R"st(
PROGRAM Fast
VAR runs : INT; always : BOOL; odd : BOOL; END_VAR
runs := runs + 1;
always := TRUE;
odd := (runs MOD 2) = 1;
END_PROGRAM

PROGRAM Slow
VAR always : BOOL; END_VAR
always := TRUE;
END_PROGRAM

CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK fast(INTERVAL := T#10ms, PRIORITY := 1);
    TASK slow(INTERVAL := T#30ms, PRIORITY := 2);
    PROGRAM f WITH fast : Fast;
    PROGRAM s WITH slow : Slow;
  END_RESOURCE
END_CONFIGURATION
)st";

struct Counted : ::testing::Test {
  void SetUp() override {
    SourceManager sources;
    Diagnostics diags;
    module = st::compileProgram({{"main.st", kFlags}}, sources, diags);
    ASSERT_NE(module, nullptr) << diags.render(sources);
    std::vector<CountedRule> rules;
    for (auto [name, task] : {std::pair{"f.always", 0u}, {"f.odd", 0u}, {"s.always", 1u}}) {
      auto ref = bc::resolveVariable(*module, name);
      ASSERT_TRUE(ref) << name;
      rules.push_back({*ref, task});
    }
    counter = RuleCounter(std::move(rules), module->tasks.size());
  }
  // Cold-starts a runtime and runs `ticks` ticks, counting after each.
  void run(int ticks) {
    VirtualClock clock;
    Runtime rt(*module, clock);
    ASSERT_TRUE(rt.coldStart());
    for (int k = 0; k < ticks; ++k) {
      ASSERT_TRUE(rt.tick());
      counter.count(rt);
    }
  }

  std::unique_ptr<bc::Module> module;
  RuleCounter counter;
};

TEST_F(Counted, EachRuleCountsTheScansOfItsOwnTaskInWhichItsFlagWasSet) {
  run(7);  // 0, 10, ..., 60 ms; the slow task scans at 0, 30 and 60 ms
  const auto& f = counter.firings();
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].scans, 7u);
  EXPECT_EQ(f[0].firstNs, 0);
  EXPECT_EQ(f[0].lastNs, 60 * kMs);
  EXPECT_EQ(f[1].scans, 4u) << "runs 1, 3, 5, 7";
  EXPECT_EQ(f[1].lastNs, 60 * kMs);
  EXPECT_EQ(f[2].scans, 3u) << "its flag stays set between its task's scans, which alone count";
  EXPECT_EQ(f[2].firstNs, 0);
  EXPECT_EQ(f[2].lastNs, 60 * kMs);
}

TEST_F(Counted, ARestartCountsAFreshRuntimeFromZero) {
  run(7);
  counter.restart();
  for (const RuleFiring& f : counter.firings()) {
    EXPECT_EQ(f.scans, 0u);
    EXPECT_EQ(f.lastNs, -1);
  }
  run(2);  // its scans count from 0 again: 0 and 10 ms
  EXPECT_EQ(counter.firings()[0].scans, 2u);
  EXPECT_EQ(counter.firings()[2].scans, 1u);
}

}  // namespace
}  // namespace virtcom::plc
