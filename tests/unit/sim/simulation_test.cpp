// The co-simulation engine on a tiny cell: one `timed` device and a PLC program doing the
// execute/done handshake, with a 10 ms task.
//
// Expected times follow from the fixed order of one base tick t (sim/simulation.hpp):
//   1. device outputs -> PLC, 2. PLC scan, 3. PLC -> device inputs, 4. devices step,
//   5. changes recorded at t, 6. stop conditions.
// For a 1 s command:
//   t = 0     scan raises exec; the device reads it in the same tick: busy, activity starts at 0.
//   t = 1000  the device's step finds the command ended (end 1000 ms <= t): done, busy drops;
//             the activity ends at 1000. The PLC has not scanned it yet.
//   t = 1010  done reaches the PLC (step 1) before the scan: one scan later. The scan drops exec
//             and counts the job; the device sees exec = 0 in the same tick and drops done.
//   t = 1020  the PLC sees done = 0 and raises exec for the next command, which starts at 1020.
// A command whose end is not on a tick reports done at the first tick after its end.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim_rig.hpp"

namespace virtcom::sim::test {
namespace {

using ::testing::ElementsAre;

// Lines are numbered: the PLC fault test expects the division's position.
const char* const kHandshakeSt =
    "(* The execute/done handshake, one command after the other. *)\n"  // 1
    "PROGRAM MAIN\n"                                                    // 2
    "VAR\n"                                                             // 3
    "  cmd : INT := 1;\n"                                               // 4
    "  exec : BOOL;\n"                                                  // 5
    "  done : BOOL;\n"                                                  // 6
    "  err : INT;\n"                                                    // 7
    "  step : INT;        (* 0 start, 1 wait for done, 2 wait for done to drop *)\n"  // 8
    "  jobs : INT;\n"                                                   // 9
    "  finished : BOOL;   (* from the scan that sees done until done drops *)\n"      // 10
    "  zero : INT;\n"                                                   // 11
    "  x : INT;\n"                                                      // 12
    "  faultAt : INT := -1;  (* divide by zero when this many jobs are done *)\n"     // 13
    "END_VAR\n"                                                         // 14
    "IF step = 2 AND NOT done THEN step := 0; END_IF\n"                 // 15
    "IF step = 0 THEN exec := TRUE; step := 1; END_IF\n"                // 16
    "IF step = 1 AND done THEN exec := FALSE; jobs := jobs + 1; step := 2; END_IF\n"  // 17
    "IF jobs = faultAt THEN x := 10 / zero; END_IF\n"                   // 18
    "finished := step = 2;\n"                                           // 19
    "END_PROGRAM\n";                                                    // 20

std::string handshakeCell(const std::string& run, const std::string& closeDuration = "1 s") {
  return "name: handshake\n"
         "plc:\n"
         "  sources: [main.st]\n"
         "  cycle_time: 10 ms\n"
         "run:\n" +
         run +
         "devices:\n"
         "  - name: Clamp\n"
         "    type: timed\n"
         "    idle_power: 10 W\n"
         "    busy_power: 100 W\n"
         "    commands:\n"
         "      1: { name: Close, duration: " +
         closeDuration +
         " }\n"
         "      2: { name: Open, duration: 500 ms }\n"
         "    wiring:\n"
         "      programNumber: MAIN.cmd\n"
         "      execute: MAIN.exec\n"
         "      done: MAIN.done\n"
         "      error: MAIN.err\n";
}

class TinyCell : public SimFiles {
 protected:
  std::unique_ptr<CellRun> load(const std::string& run, const std::string& closeDuration = "1 s") {
    return loadCell(handshakeCell(run, closeDuration), {{"main.st", kHandshakeSt}});
  }
};

TEST_F(TinyCell, HandshakeTimesFollowTheSteppingOrder) {
  auto r = load("  cycle_done: MAIN.finished\n  cycles: 2\n  record: [MAIN.done, MAIN.jobs]\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_THAT(changesText(r->trace()),
              ElementsAre("0 ms Clamp.execute = 1", "0 ms Clamp.busy = 1",                         //
                          "1000 ms Clamp.done = 1", "1000 ms Clamp.busy = 0",                      //
                          "1010 ms Clamp.execute = 0", "1010 ms Clamp.done = 0",                   //
                          "1010 ms MAIN.done = 1", "1010 ms MAIN.jobs = 1",                        // seen one scan later
                          "1020 ms Clamp.execute = 1", "1020 ms Clamp.busy = 1",                   //
                          "1020 ms MAIN.done = 0",                                                 //
                          "2020 ms Clamp.done = 1", "2020 ms Clamp.busy = 0",                      //
                          "2030 ms Clamp.execute = 0", "2030 ms Clamp.done = 0",                   //
                          "2030 ms MAIN.done = 1", "2030 ms MAIN.jobs = 2"));
  EXPECT_THAT(activitiesText(r->trace()), ElementsAre("Clamp Close 0 ms .. 1000 ms", "Clamp Close 1020 ms .. 2020 ms"));
  // initial values: the command number is already 1 (its initial value) before the first scan
  const Trace& t = r->trace();
  ASSERT_EQ(t.signals.size(), 7u);
  EXPECT_EQ(t.signals[0].name, "Clamp.programNumber");
  EXPECT_EQ(t.signals[0].initial, 1u);
  EXPECT_EQ(r->simulation->ticks(), 204u);  // ticks at 0, 10, ..., 2030 ms
  EXPECT_EQ(r->simulation->nowNs(), 2030 * kMs);
}

TEST_F(TinyCell, CycleDoneMeasuresTheLastCycle) {
  auto r = load("  cycle_done: MAIN.finished\n  cycles: 2\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  const Trace& t = r->trace();
  EXPECT_EQ(t.endMessage, "2 cycle(s) completed");
  EXPECT_EQ(t.cyclesCompleted, 2u);
  EXPECT_EQ(t.cycleStartNs, 1010 * kMs);  // first rising edge of MAIN.finished
  EXPECT_EQ(t.cycleEndNs, 2030 * kMs);
  EXPECT_EQ(t.endNs, 2030 * kMs);
  report::Kpis k = r->kpis();
  EXPECT_TRUE(k.cycleMeasured);
  EXPECT_EQ(k.cycleTimeNs, 1020 * kMs);
  // energy: 10 W over the whole run + 100 W x 1 s per command
  ASSERT_EQ(t.totals.size(), 1u);
  EXPECT_EQ(t.totals[0].busyNs, 2000 * kMs);
  EXPECT_NEAR(t.totals[0].energyJ, 10 * 2.03 + 2 * 100.0, 1e-9);
  EXPECT_NEAR(t.activities[0].energyJ, 100.0, 1e-9);
}

TEST_F(TinyCell, OneCycleFromTimeZero) {
  auto r = load("  cycle_done: MAIN.finished\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_EQ(r->trace().endMessage, "1 cycle(s) completed");
  EXPECT_EQ(r->trace().cycleStartNs, 0);
  EXPECT_EQ(r->trace().cycleEndNs, 1010 * kMs);
  EXPECT_EQ(r->kpis().cycleTimeNs, 1010 * kMs);
}

TEST_F(TinyCell, DoneAtTheFirstTickAfterAnEndBetweenTicks) {
  auto r = load("  cycle_done: MAIN.finished\n", "1005 ms");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_THAT(activitiesText(r->trace()), ElementsAre("Clamp Close 0 ms .. 1010 ms"));
  EXPECT_EQ(r->trace().cycleEndNs, 1020 * kMs);
  // the command's energy is its exact duration's; the bar (busy time) runs to the done tick
  EXPECT_NEAR(r->trace().activities[0].energyJ, 100.5, 1e-9);
  EXPECT_EQ(r->trace().totals[0].busyNs, 1010 * kMs);
}

TEST_F(TinyCell, UntilStopsWhenTheConditionHolds) {
  // `until` takes over from `cycles`: the run goes on past the first cycle
  auto r = load("  cycle_done: MAIN.finished\n  until: \"MAIN.jobs >= 2\"\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_EQ(r->trace().endMessage, "'MAIN.jobs >= 2' became true");
  EXPECT_EQ(r->trace().endNs, 2030 * kMs);
  EXPECT_EQ(r->trace().cyclesCompleted, 2u);
}

TEST_F(TinyCell, UntilSetAfterLoadingLikeTheCommandLineOption) {
  auto r = load("  cycle_done: MAIN.finished\n  cycles: 100\n");
  ASSERT_NE(r, nullptr);
  Diagnostics d;
  r->cell->run.until = cell::parseCondition(*r->cell->module, "MAIN.jobs = 3", {}, d);
  ASSERT_FALSE(d.hasErrors());
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_EQ(r->trace().endNs, 3050 * kMs);  // job n is counted at n x 1020 ms - 10 ms
}

TEST_F(TinyCell, TimeLimitOfTheCell) {
  auto r = load("  cycle_done: MAIN.finished\n  time_limit: 500 ms\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::TimeLimit);
  const Trace& t = r->trace();
  EXPECT_EQ(t.endNs, 500 * kMs);
  EXPECT_EQ(t.endMessage, "time limit reached without meeting the stop condition");
  EXPECT_THAT(activitiesText(t), ElementsAre("Clamp Close 0 ms .. running"));
  EXPECT_EQ(t.totals[0].busyNs, 500 * kMs);  // a running command counts up to the end
  EXPECT_EQ(t.cyclesCompleted, 0u);
  EXPECT_EQ(r->kpis().devices[0].running, 1u);
}

// Regression test (found by the cell/sim test suite).
TEST_F(TinyCell, RunWithoutACompletedCycleHasNoMeasuredCycle) {
  auto r = load("  cycle_done: MAIN.finished\n  time_limit: 500 ms\n");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::TimeLimit);
  report::Kpis k = r->kpis();
  EXPECT_EQ(k.cyclesCompleted, 0u);
  EXPECT_FALSE(k.cycleMeasured);
  EXPECT_NE(r->json().find("\"measured\": false"), std::string::npos);
}

TEST_F(TinyCell, TimeLimitOptionOverridesTheCell) {
  auto r = load("  cycle_done: MAIN.finished\n  time_limit: 10 s\n");
  ASSERT_NE(r, nullptr);
  SimOptions o;
  o.timeLimitNs = 300 * kMs;
  EXPECT_EQ(r->run(o), RunEnd::TimeLimit);
  EXPECT_EQ(r->trace().endNs, 300 * kMs);
}

TEST_F(TinyCell, PlcFaultEndsTheRunWithItsLocation) {
  auto r = load("  cycle_done: MAIN.finished\n  cycles: 5\n");
  ASSERT_NE(r, nullptr);
  SimOptions o;
  o.preset = presets({{"MAIN.faultAt", "1"}});
  EXPECT_EQ(r->run(o), RunEnd::PlcFault);
  const Trace& t = r->trace();
  EXPECT_EQ(t.endNs, 1010 * kMs);  // the scan that counts the first job
  EXPECT_EQ(stripDir(t.endMessage), "division by zero at main.st:18:24 (task MainTask)");
  ASSERT_EQ(t.faults.size(), 1u);
  EXPECT_EQ(t.faults[0].timeNs, 1010 * kMs);
  EXPECT_EQ(t.faults[0].source, "PLC");
  EXPECT_EQ(t.faults[0].message, t.endMessage);
  EXPECT_EQ(r->simulation->plc().state(), plc::PlcState::Fault);
}

TEST_F(TinyCell, UnknownCommandIsADeviceError) {
  auto r = load("  cycle_done: MAIN.finished\n");
  ASSERT_NE(r, nullptr);
  SimOptions o;
  o.preset = presets({{"MAIN.cmd", "7"}});
  EXPECT_EQ(r->run(o), RunEnd::DeviceError);
  const Trace& t = r->trace();
  EXPECT_EQ(t.endNs, 0);
  EXPECT_EQ(t.endMessage, "Clamp reported error 10");
  EXPECT_THAT(activitiesText(t), ElementsAre("Clamp UnknownCommand 0 ms .. 0 ms error 10"));
  ASSERT_EQ(t.faults.size(), 1u);
  EXPECT_EQ(t.faults[0].source, "Clamp");
  EXPECT_EQ(t.faults[0].message, "Clamp reported error 10");
  EXPECT_EQ(r->kpis().errors, 1u);
}

TEST_F(TinyCell, DeviceErrorDoesNotStopWhenSwitchedOff) {
  auto r = load("  cycle_done: MAIN.finished\n  stop_on_device_error: false\n  time_limit: 100 ms\n");
  ASSERT_NE(r, nullptr);
  SimOptions o;
  o.preset = presets({{"MAIN.cmd", "7"}});
  EXPECT_EQ(r->run(o), RunEnd::TimeLimit);
  EXPECT_TRUE(r->trace().faults.empty());
  EXPECT_THAT(activitiesText(r->trace()), ElementsAre("Clamp UnknownCommand 0 ms .. 0 ms error 10"));
}

TEST_F(TinyCell, PresetsAreAppliedBeforeTheFirstScan) {
  // the first scan already sends command 2 (Open), and the command port starts at 2
  auto r = load("  cycle_done: MAIN.finished\n");
  ASSERT_NE(r, nullptr);
  SimOptions o;
  o.preset = presets({{"MAIN.cmd", "2"}});
  EXPECT_EQ(r->run(o), RunEnd::Completed);
  EXPECT_THAT(activitiesText(r->trace()), ElementsAre("Clamp Open 0 ms .. 500 ms"));
  EXPECT_EQ(r->trace().signals[0].name, "Clamp.programNumber");
  EXPECT_EQ(r->trace().signals[0].initial, 2u);
  EXPECT_EQ(r->trace().endNs, 510 * kMs);
}

TEST_F(TinyCell, SingleSteppingGivesTheSameTraceAsRun) {
  auto a = load("  cycle_done: MAIN.finished\n  cycles: 2\n");
  ASSERT_NE(a, nullptr);
  SimOptions everyTick;  // step() never jumps, so the JSON's run.time matches only this run's
  everyTick.eventTime = false;
  a->run(everyTick);
  auto b = load("  cycle_done: MAIN.finished\n  cycles: 2\n");
  ASSERT_NE(b, nullptr);
  b->simulation = std::make_unique<sim::Simulation>(*b->cell, everyTick);
  uint64_t steps = 1;
  while (b->simulation->step()) ++steps;
  EXPECT_EQ(steps, 204u);
  EXPECT_FALSE(b->simulation->step());  // stays ended
  EXPECT_EQ(b->trace().end, RunEnd::Completed);
  EXPECT_EQ(b->json(), a->json());
  EXPECT_EQ(b->csv(), a->csv());
}

TEST_F(TinyCell, VariableRecordedTwiceIsOneSignal) {
  auto r = load("  cycle_done: MAIN.finished\n  record: [MAIN.jobs, MAIN.jobs]\n");
  ASSERT_NE(r, nullptr);
  r->run();
  size_t named = 0;
  for (const auto& s : r->trace().signals) named += s.name == "MAIN.jobs";
  EXPECT_EQ(named, 1u);
}

// Two robots whose procedures both go to a location in zone Shared. Robot1 moves there at once;
// Robot2 waits first, then enters the zone at the start of its move.
std::string twoRobotsCell(const std::string& wait, const std::string& run) {
  return "name: two-robots\n"
         "plc:\n"
         "  sources: [robots.st]\n"
         "run:\n" +
         run +
         "zones: [Shared]\n"
         "devices:\n"
         "  - name: Robot1\n"
         "    type: robot\n"
         "    wiring: MAIN.R1\n"
         "    max_speed: 1000 mm/s\n"
         "    acceleration: 4000 mm/s^2\n"
         "    locations:\n"
         "      home: \"0, 0, 0 mm\"\n"
         "      spot: { at: \"1000, 0, 0 mm\", zone: Shared }\n"
         "    procedures:\n"
         "      1: { name: PlaceLeft, steps: [move spot, move home] }\n"
         "  - name: Robot2\n"
         "    type: robot\n"
         "    wiring: MAIN.R2\n"
         "    max_speed: 1000 mm/s\n"
         "    acceleration: 4000 mm/s^2\n"
         "    locations:\n"
         "      home: \"0, 500, 0 mm\"\n"
         "      spot: { at: \"1000, 500, 0 mm\", zone: Shared }\n"
         "    procedures:\n"
         "      1: { name: PlaceRight, steps: [wait " +
         wait + ", move spot, move home] }\n";
}

const char* const kRobotsSt = R"(TYPE ST_Robot :
STRUCT
  procedureNumber : INT;
  execute : BOOL;
  done : BOOL;
  error : INT;
  busy : BOOL;
END_STRUCT
END_TYPE

PROGRAM MAIN
VAR
  R1, R2 : ST_Robot;
END_VAR
R1.procedureNumber := 1; R1.execute := NOT R1.done;
R2.procedureNumber := 1; R2.execute := NOT R2.done;
END_PROGRAM
)";

TEST_F(TinyCell, TwoRobotsInOneZoneCollide) {
  auto r = loadCell(twoRobotsCell("0.5 s", "  time_limit: 10 s\n"), {{"robots.st", kRobotsSt}});
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Collision);
  const Trace& t = r->trace();
  EXPECT_EQ(t.endNs, 500 * kMs);
  EXPECT_EQ(t.endMessage, "robots collided in a shared zone");
  ASSERT_EQ(t.collisions.size(), 1u);
  const CollisionRecord& c = t.collisions[0];
  EXPECT_EQ(c.timeNs, 500 * kMs);
  EXPECT_EQ(t.labels[c.zone], "Shared");
  EXPECT_EQ(t.devices[c.deviceA].name, "Robot1");
  EXPECT_EQ(t.labels[c.activityA], "PlaceLeft");
  EXPECT_EQ(t.devices[c.deviceB].name, "Robot2");
  EXPECT_EQ(t.labels[c.activityB], "PlaceRight");
}

TEST_F(TinyCell, CollisionTimeIsExactBetweenTicks) {
  auto r = loadCell(twoRobotsCell("505 ms", "  time_limit: 10 s\n"), {{"robots.st", kRobotsSt}});
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Collision);
  ASSERT_EQ(r->trace().collisions.size(), 1u);
  EXPECT_EQ(r->trace().collisions[0].timeNs, 505 * kMs);  // the move's exact start
  EXPECT_EQ(r->trace().endNs, 510 * kMs);                 // seen at the next tick
}

TEST_F(TinyCell, CollisionIsRecordedWithoutStoppingWhenSwitchedOff) {
  auto r = loadCell(twoRobotsCell("0.5 s", "  time_limit: 3 s\n  stop_on_collision: false\n"), {{"robots.st", kRobotsSt}});
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::TimeLimit);
  ASSERT_GE(r->trace().collisions.size(), 1u);
  EXPECT_EQ(r->trace().collisions[0].timeNs, 500 * kMs);
  EXPECT_EQ(r->trace().endNs, 3000 * kMs);
}

// A device output wired to a located input (AT %IX) reaches the program: it goes into the input
// image, which the scan copies into the %I area (written into the area, it would be overwritten).
class LocatedInputCell : public SimFiles {};

TEST_F(LocatedInputCell, SensorWiredToAnAtIxVariableReachesTheProgram) {
  auto r = loadCell(R"(name: located
plc:
  sources: [main.st]
  cycle_time: 10 ms
run:
  until: "MAIN.seen"
  time_limit: 1 s
world:
  facts:
    pressed: true
devices:
  - name: Button
    type: sensor
    fact: pressed
    wiring: {value: MAIN.button}
)",
                    {{"main.st", "PROGRAM MAIN\nVAR\n  button AT %IX0.3 : BOOL;\n  seen : BOOL;\nEND_VAR\n"
                                 "seen := button;\nEND_PROGRAM\n"}});
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->run(), RunEnd::Completed);
  EXPECT_EQ(r->trace().endNs, 10 * kMs);  // written after the first scan, read by the second
}

}  // namespace
}  // namespace virtcom::sim::test
