// The same cell gives the same trace, byte for byte (docs/cell-file.md "How a run steps"), and
// skipping repeated PLC scans (SimOptions::skipRepeatedScans) is exact: the traces with and
// without it are identical. Traces are compared as the JSON report (activities, collisions,
// KPIs) and the CSV of every signal change. Event-driven time (SimOptions::eventTime) is exact
// too: jumping over idle ticks gives the traces of stepping every one (the e2e suite
// event_time_e2e_tests compares every example cell's outputs the same way).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim_rig.hpp"

namespace virtcom::sim::test {
namespace {

// Compares two texts and, when they differ, shows the first differing line instead of both.
::testing::AssertionResult sameText(const std::string& a, const std::string& b) {
  if (a == b) return ::testing::AssertionSuccess();
  size_t at = 0;
  while (at < a.size() && at < b.size() && a[at] == b[at]) ++at;
  size_t lineStart = a.rfind('\n', at == 0 ? 0 : at - 1);
  lineStart = lineStart == std::string::npos ? 0 : lineStart + 1;
  auto lineOf = [&](const std::string& s) { return s.substr(lineStart, s.find('\n', lineStart) - lineStart); };
  return ::testing::AssertionFailure() << "texts differ (" << a.size() << " vs " << b.size()
                                       << " bytes) first at byte " << at << ":\n  " << lineOf(a) << "\n  " << lineOf(b);
}

// The JSON report without its `run.time` object, the one part that says how the clock went.
std::string withoutTime(const std::string& json) {
  const size_t from = json.find("\"time\": {");
  if (from == std::string::npos) return json;
  return json.substr(0, from) + json.substr(json.find('}', from) + 1);
}

TEST(GearboxDeterminism, TwoRunsGiveByteIdenticalTraces) {
  auto first = runGearbox(3);
  auto second = runGearbox(3);
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(first->trace().end, RunEnd::Completed);
  EXPECT_TRUE(sameText(first->json(), second->json()));
  EXPECT_TRUE(sameText(first->csv(), second->csv()));
  EXPECT_GT(first->trace().changes.size(), 1000u);  // the comparison covers a real run
}

class ScanSkipping : public ::testing::TestWithParam<int> {};

// Sequence 1 is serial (long idle PLC stretches while one device works), 3 overlaps devices.
TEST_P(ScanSkipping, IsExactOnTheGearbox) {
  auto skipping = runGearbox(GetParam(), true);
  auto scanning = runGearbox(GetParam(), false);
  ASSERT_NE(skipping, nullptr);
  ASSERT_NE(scanning, nullptr);
  EXPECT_EQ(skipping->trace().end, RunEnd::Completed);
  EXPECT_TRUE(sameText(withoutTime(skipping->json()), withoutTime(scanning->json())));
  EXPECT_TRUE(sameText(skipping->csv(), scanning->csv()));
  // the comparison is not vacuous: scans were really skipped in one run and not in the other
  EXPECT_GT(skipping->simulation->plc().stats(0).skippedScans, 0u);
  EXPECT_EQ(scanning->simulation->plc().stats(0).skippedScans, 0u);
  EXPECT_EQ(skipping->simulation->plc().stats(0).scans, scanning->simulation->plc().stats(0).scans);
}

INSTANTIATE_TEST_SUITE_P(Gearbox, ScanSkipping, ::testing::Values(1, 3),
                         [](const auto& info) { return "Sequence" + std::to_string(info.param); });

class EventTime : public ::testing::TestWithParam<int> {};

// Sequence 4 ends in a collision, 1 waits longest on single devices.
TEST_P(EventTime, IsExactOnTheGearbox) {
  auto jumping = runGearbox(GetParam(), true, true);
  auto stepping = runGearbox(GetParam(), true, false);
  ASSERT_NE(jumping, nullptr);
  ASSERT_NE(stepping, nullptr);
  EXPECT_TRUE(sameText(withoutTime(jumping->json()), withoutTime(stepping->json())));
  EXPECT_TRUE(sameText(jumping->csv(), stepping->csv()));
  const TimeSteps& jumped = jumping->trace().time;
  const TimeSteps& stepped = stepping->trace().time;
  EXPECT_TRUE(jumped.eventDriven);
  EXPECT_FALSE(stepped.eventDriven);
  EXPECT_GT(jumped.ticksSkipped, 0u);
  EXPECT_GT(jumped.jumps, 0u);
  EXPECT_EQ(stepped.ticksSkipped, 0u);
  EXPECT_EQ(jumped.ticks, stepped.ticks);
  EXPECT_EQ(jumping->simulation->ticks(), stepping->simulation->ticks());
  // a skipped tick is a repeated scan the PLC would have skipped anyway: same statistics
  EXPECT_EQ(jumping->simulation->plc().stats(0).scans, stepping->simulation->plc().stats(0).scans);
  EXPECT_EQ(jumping->simulation->plc().stats(0).skippedScans, stepping->simulation->plc().stats(0).skippedScans);
}

INSTANTIATE_TEST_SUITE_P(Gearbox, EventTime, ::testing::Values(1, 2, 3, 4),
                         [](const auto& info) { return "Sequence" + std::to_string(info.param); });

// A handshake with a 250 ms TON dwell between three 1 s commands. The timer reads the clock in
// every scan while it runs, so those scans must never be skipped even when nothing else moves.
const char* const kTonSt = R"(PROGRAM MAIN
VAR
  cmd : INT := 1;
  exec : BOOL;
  done : BOOL;
  step : INT;      (* 0 start, 1 wait for done, 2 wait for done to drop, 3 dwell *)
  jobs : INT;
  finished : BOOL;
  dwell : TON;
END_VAR
IF step = 2 AND NOT done THEN step := 3; END_IF
dwell(IN := step = 3, PT := T#250MS);
IF step = 3 AND dwell.Q THEN step := 0; END_IF
IF step = 0 AND jobs < 3 THEN exec := TRUE; step := 1; END_IF
IF step = 1 AND done THEN exec := FALSE; jobs := jobs + 1; step := 2; END_IF
finished := jobs >= 3;
END_PROGRAM
)";

const char* const kTonCell = R"(name: dwell
plc:
  sources: [main.st]
  cycle_time: 10 ms
run:
  cycle_done: MAIN.finished
  record: [MAIN.dwell.Q, MAIN.jobs]
devices:
  - name: Clamp
    type: timed
    busy_power: 50 W
    commands:
      1: { name: Close, duration: 1 s }
    wiring:
      programNumber: MAIN.cmd
      execute: MAIN.exec
      done: MAIN.done
)";

class TonCell : public SimFiles {};

TEST_F(TonCell, DwellTimesAreExact) {
  auto r = loadCell(kTonCell, {{"main.st", kTonSt}});
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  // job n+1 starts 250 ms after the scan that sees done drop (see simulation_test.cpp for the
  // tick order): done at 1000, seen 1010, dropped 1010, seen dropped 1020, dwell to 1270.
  EXPECT_THAT(activitiesText(r->trace()), ::testing::ElementsAre("Clamp Close 0 ms .. 1000 ms",
                                                                 "Clamp Close 1270 ms .. 2270 ms",
                                                                 "Clamp Close 2540 ms .. 3540 ms"));
  EXPECT_EQ(r->trace().endNs, 3550 * kMs);
}

TEST_F(TonCell, ScanSkippingIsExactWithTimers) {
  auto skipping = loadCell(kTonCell, {{"main.st", kTonSt}});
  auto scanning = loadCell(kTonCell, {{"main.st", kTonSt}});
  ASSERT_NE(skipping, nullptr);
  ASSERT_NE(scanning, nullptr);
  SimOptions on, off;
  on.skipRepeatedScans = true;
  off.skipRepeatedScans = false;
  EXPECT_EQ(skipping->run(on), RunEnd::Completed);
  EXPECT_EQ(scanning->run(off), RunEnd::Completed);
  EXPECT_TRUE(sameText(withoutTime(skipping->json()), withoutTime(scanning->json())));
  EXPECT_TRUE(sameText(skipping->csv(), scanning->csv()));
  // scans were skipped while a command ran (the PLC only waits), never in the 2 x 26 scans
  // of the timer runs (1020..1270 ms, 2290..2540 ms)
  const uint64_t skipped = skipping->simulation->plc().stats(0).skippedScans;
  EXPECT_EQ(skipping->simulation->ticks(), 356u);
  EXPECT_GT(skipped, 200u);
  EXPECT_LE(skipped, 356u - 2 * 26);
}

// A running TON reads the clock every scan: no jump over a dwell, only over the clamp's commands
// (the PLC waits on done), and the results are those of stepping every tick.
TEST_F(TonCell, EventTimeJumpsOnlyWhileNoTimerRuns) {
  auto jumping = loadCell(kTonCell, {{"main.st", kTonSt}});
  auto stepping = loadCell(kTonCell, {{"main.st", kTonSt}});
  ASSERT_NE(jumping, nullptr);
  ASSERT_NE(stepping, nullptr);
  SimOptions on, off;
  off.eventTime = false;
  EXPECT_EQ(jumping->run(on), RunEnd::Completed);
  EXPECT_EQ(stepping->run(off), RunEnd::Completed);
  EXPECT_TRUE(sameText(withoutTime(jumping->json()), withoutTime(stepping->json())));
  EXPECT_TRUE(sameText(jumping->csv(), stepping->csv()));
  const TimeSteps& t = jumping->trace().time;
  EXPECT_EQ(t.ticks, 356u);
  EXPECT_GT(t.ticksSkipped, 200u);
  EXPECT_LE(t.ticksSkipped, 356u - 2 * 26);
  EXPECT_GE(t.jumps, 3u);  // one per command at least
}

}  // namespace
}  // namespace virtcom::sim::test
