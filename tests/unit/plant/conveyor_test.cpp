// The conveyor: parts moving at belt speed, end stoppers, queueing, sensors, spawning, picking
// at the end through end_fact, next-event times, and part kinds with kind-detecting sensors,
// pushers, bins and discharge.
#include <gtest/gtest.h>

#include <string>

#include "plant/conveyor.hpp"
#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

const char* kBelt = R"(speed: 100 mm/s
length: 1000 mm
part_length: 100 mm
initial_parts: [0 mm]
power: 50 W
sensors:
  entry: 50 mm
  atEnd: 990 mm
end_fact: partAtEnd
)";

TEST(Conveyor, PartTravelsAtBeltSpeedAndStopsAtTheEnd) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", kBelt));
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  rig.tick();
  EXPECT_TRUE(rig.getBool("Belt.entry"));
  EXPECT_FALSE(rig.getBool("Belt.moving"));
  rig.setBool("Belt.run", true);
  rig.tick();
  const int64_t start = rig.now;
  EXPECT_TRUE(rig.getBool("Belt.moving"));
  rig.tick(kS);
  EXPECT_NEAR(c->partPositionM(0), 0.1, 1e-12);
  EXPECT_FALSE(rig.getBool("Belt.entry"));  // rear edge at 100 mm passed the 50 mm sensor
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("Belt.atEnd"); }));
  EXPECT_EQ(rig.now - start, 8900 * kMs);  // front edge from 100 mm to 990 mm
  EXPECT_FALSE(rig.fact("partAtEnd"));
  ASSERT_TRUE(rig.tickUntil([&] { return rig.fact("partAtEnd"); }));
  EXPECT_EQ(rig.now - start, 9000 * kMs);
  rig.tick(5 * kS);
  EXPECT_NEAR(c->partPositionM(0), 0.9, 1e-9);  // held by the end stopper
  EXPECT_TRUE(rig.getBool("Belt.atEnd"));
}

// A scenario's `parameter:` step (docs/scenarios.md): the speed changes mid-run, the part goes
// on from where it is; the belt's geometry does not change.
TEST(Conveyor, TakesANewSpeedMidRun) {
  PlantRig rig, edits;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", kBelt));
  std::string faster = kBelt;
  faster.replace(faster.find("100 mm/s"), 8, "200 mm/s");
  Device* edited = edits.add("conveyor", "Belt", faster);
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  ASSERT_NE(edited, nullptr) << edits.renderedDiags();
  EXPECT_TRUE(c->changesParameter("speed"));
  EXPECT_TRUE(c->changesParameter("spawn_interval"));
  EXPECT_FALSE(c->changesParameter("length"));
  EXPECT_FALSE(c->changesParameter("power"));
  rig.setBool("Belt.run", true);
  rig.tick();
  rig.tick(kS);
  EXPECT_NEAR(c->partPositionM(0), 0.1, 1e-9);
  c->swapParameters(*edited);
  rig.tick(kS);
  EXPECT_NEAR(c->partPositionM(0), 0.3, 1e-9);
  EXPECT_NEAR(c->params().speed, 0.2, 1e-12);
  EXPECT_EQ(c->params().lengthNm, 1'000'000'000);
}

TEST(Conveyor, TakingThePartAtTheEndRemovesIt) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", kBelt));
  ASSERT_NE(c, nullptr);
  rig.setBool("Belt.run", true);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.fact("partAtEnd"); }));
  rig.setFact("partAtEnd", false);  // e.g. a robot's `grip partAtEnd`
  rig.tick();
  EXPECT_EQ(c->partCount(), 0u);
  EXPECT_FALSE(rig.getBool("Belt.atEnd"));
  EXPECT_FALSE(rig.fact("partAtEnd"));
}

TEST(Conveyor, PartsQueueWithoutOverlapAndReverseRunsBack) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", "speed: 1 m/s\nlength: 1 m\npart_length: 200 mm\ninitial_parts: [0 mm, 300 mm]\n"));
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  rig.setBool("Belt.run", true);
  rig.tick();
  rig.tick(5 * kS);
  EXPECT_NEAR(c->partPositionM(1), 0.8, 1e-9);
  EXPECT_NEAR(c->partPositionM(0), 0.6, 1e-9);
  rig.setBool("Belt.reverse", true);
  rig.tick();
  rig.tick(5 * kS);
  EXPECT_NEAR(c->partPositionM(0), 0.0, 1e-9);
  EXPECT_NEAR(c->partPositionM(1), 0.2, 1e-9);
}

TEST(Conveyor, SpawnsPartsWhileRunning) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", "speed: 100 mm/s\nlength: 1 m\npart_length: 100 mm\nspawn_interval: 2 s\n"));
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  rig.tick();
  EXPECT_EQ(c->partCount(), 0u);
  rig.setBool("Belt.run", true);
  rig.tick();
  EXPECT_EQ(c->partCount(), 1u);  // first part at the first running tick
  rig.tickUntil([&] { return c->partCount() == 2; });
  EXPECT_NEAR(c->partPositionM(1), 0.2, 1e-9);
  // a full belt stops spawning: 10 parts of 100 mm on 1 m
  rig.tick(200 * kS);
  EXPECT_EQ(c->partCount(), 10u);
  for (size_t i = 1; i < c->partCount(); ++i) EXPECT_GE(c->partPositionM(i) - c->partPositionM(i - 1), 0.1 - 1e-9);
}

TEST(Conveyor, NextEventIsTheNextSensorEdge) {
  PlantRig rig;
  Device* c = rig.add("conveyor", "Belt", kBelt);
  ASSERT_NE(c, nullptr);
  rig.tick();
  EXPECT_EQ(c->nextEventNs(), INT64_MAX);
  rig.setBool("Belt.run", true);
  rig.tick();
  // The rear edge (0) passes the entry sensor (50 mm) after 0.5 s. The next event is a tick (1 ms
  // here) at which the sensor may have changed: never after the change (the ticks before it can
  // be skipped exactly), at most a tick before it (a tick moves at most round(speed x tick) + 1 nm).
  const int64_t next = c->nextEventNs();
  EXPECT_EQ((next - rig.now) % kMs, 0);
  ASSERT_TRUE(rig.tickUntil([&] { return !rig.getBool("Belt.entry"); }));
  EXPECT_LE(next, rig.now);
  EXPECT_GE(next, rig.now - kMs);
}

TEST(Conveyor, RunningPeriodsAreActivitiesWithEnergy) {
  PlantRig rig;
  Device* c = rig.add("conveyor", "Belt", kBelt);
  ASSERT_NE(c, nullptr);
  rig.tick();
  rig.setBool("Belt.run", true);
  rig.tick();
  rig.tick(2 * kS);
  rig.setBool("Belt.run", false);
  rig.tick();
  ASSERT_EQ(rig.trace.activities.size(), 1u);
  EXPECT_EQ(rig.label(rig.trace.activities[0]), "Running");
  EXPECT_EQ(rig.trace.activities[0].endNs - rig.trace.activities[0].startNs, 2001 * kMs);
  EXPECT_NEAR(rig.trace.activities[0].energyJ, 50 * 2.001, 1e-9);
  rig.finish();
  EXPECT_EQ(rig.trace.totals[c->traceIndex()].busyNs, 2001 * kMs);
}

TEST(Conveyor, ConfigErrors) {
  PlantRig rig;
  EXPECT_EQ(rig.add("conveyor", "C", "speed: 0 mm/s\nlength: 1 m\ninitial_parts: [0 mm, 50 mm, 2 m]\nsensors:\n  run: 5 mm\n"), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("C.yaml:1:8: error[C010]: 'speed' must be greater than 0"), std::string::npos) << out;
  EXPECT_NE(out.find("C.yaml:3:30: error[C010]: 'initial_parts': part does not fit"), std::string::npos) << out;
  EXPECT_NE(out.find("'initial_parts': parts overlap"), std::string::npos) << out;
  EXPECT_NE(out.find("C.yaml:5:3: error[C010]: sensor name 'run' clashes"), std::string::npos) << out;
}

const char* kSortingBelt = R"(speed: 100 mm/s
length: 1000 mm
part_length: 100 mm
spawn_interval: 2 s
spawn_count: 4
part_kinds: [steel, plastic, steel, bad]
discharge: true
sensors:
  metal: {at: 250 mm, detects: [steel]}
  any: 250 mm
  atGate: 300 mm
pushers:
  gate: 300 mm
)";

// Spawned parts take their kinds from the pattern; a kind-detecting sensor sees only its kinds;
// a pusher pushes the part at it into its bin; the rest run off the end into the end bin. (The
// gate is 50 mm after the metal sensor: the part the sensor marks is the next at the gate, the
// one before it, 200 mm ahead, has passed it.)
TEST(Conveyor, KindsPushersAndDischargeSortEveryPartIntoOneBin) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", kSortingBelt));
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  rig.setBool("Belt.run", true);
  int metalSeen = 0, anySeen = 0;
  bool lastMetal = false, lastAny = false, steelDue = false;
  for (int i = 0; i < 20000; ++i) {  // 20 s: all four parts spawned (0, 2, 4, 6 s) and gone
    rig.tick();
    const bool metal = rig.getBool("Belt.metal"), any = rig.getBool("Belt.any");
    metalSeen += metal && !lastMetal;
    anySeen += any && !lastAny;
    lastMetal = metal;
    lastAny = any;
    // the controller: a steel part seen by the metal sensor is pushed off when it is at the gate
    if (metal) steelDue = true;
    const bool push = steelDue && rig.getBool("Belt.atGate");
    if (rig.getBool("Belt.gate") && !rig.getBool("Belt.atGate")) steelDue = false;
    rig.setBool("Belt.gate", push || (rig.getBool("Belt.gate") && rig.getBool("Belt.atGate")));
  }
  EXPECT_EQ(anySeen, 4);
  EXPECT_EQ(metalSeen, 2);
  EXPECT_EQ(c->partCount(), 0u);
  EXPECT_EQ(rig.getNumber("Belt.produced_steel"), 2);
  EXPECT_EQ(rig.getNumber("Belt.produced_plastic"), 1);
  EXPECT_EQ(rig.getNumber("Belt.produced_bad"), 1);
  EXPECT_EQ(rig.getNumber("Belt.gate_steel"), 2);
  EXPECT_EQ(rig.getNumber("Belt.end_plastic"), 1);
  EXPECT_EQ(rig.getNumber("Belt.end_bad"), 1);
  EXPECT_EQ(rig.getNumber("Belt.end_steel"), 0);
  EXPECT_EQ(c->binCount(0, 0), 2);  // bin 0 (gate), kind 0 (steel)
}

// A pusher takes exactly the part covering its position, at the tick its command is on.
TEST(Conveyor, PusherTakesThePartInFrontOfIt) {
  PlantRig rig;
  auto* c = static_cast<Conveyor*>(rig.add("conveyor", "Belt", R"(speed: 100 mm/s
length: 1000 mm
part_length: 100 mm
initial_parts: [0 mm, 400 mm]
pushers:
  off: 450 mm
)"));
  ASSERT_NE(c, nullptr) << rig.renderedDiags();
  rig.setBool("Belt.off", true);
  rig.tick();
  EXPECT_EQ(c->partCount(), 1u);
  EXPECT_EQ(rig.getNumber("Belt.off_parts"), 1);  // without part_kinds the one kind is "parts"
  EXPECT_NEAR(c->partPositionM(0), 0.0, 1e-12);
}

TEST(Conveyor, KindAndPusherMistakes) {
  PlantRig rig;
  EXPECT_EQ(rig.add("conveyor", "C", R"(speed: 100 mm/s
length: 1 m
part_kinds: steel
sensors:
  cam: {at: 100 mm, detects: [glass]}
  run: 200 mm
pushers:
  cam: 300 mm
  far: 2 m
)"),
            nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_NE(out.find("C.yaml:3:13: error[C010]: 'part_kinds' must be a list of kind names"), std::string::npos) << out;
  EXPECT_NE(out.find("C.yaml:5:31: error[C010]: 'detects': 'glass' is not one of the conveyor's part_kinds (none declared)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("C.yaml:6:3: error[C010]: sensor name 'run' clashes with a conveyor port"), std::string::npos) << out;
  EXPECT_NE(out.find("C.yaml:8:3: error[C010]: pusher name 'cam' clashes with a conveyor port"), std::string::npos) << out;
  EXPECT_NE(out.find("C.yaml:9:8: error[C010]: pusher 'far' is not on the belt"), std::string::npos) << out;
}

}  // namespace
}  // namespace virtcom::plant::test
