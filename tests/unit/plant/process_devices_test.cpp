// The process devices (tank, valve, pump, heater, level switch, temperature sensor): their
// physics against closed-form results (fill time = volume / flow, heating rate = P / (m·c),
// mixing, heat loss, hysteresis, sensor lag) and the mistakes of their entries.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/tank.hpp"
#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

double seconds(int64_t ns) { return static_cast<double>(ns) * 1e-9; }

// 100 l filled at 10 l/s: full 10 s after the valve opened (at the first tick, 1 ms), to the
// tick; the level switch at 90 % on after 9 s.
TEST(Tank, FillTimeIsVolumeOverFlow) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\nheight: 1 m\n"), nullptr);
  ASSERT_NE(rig.add("valve", "V", "to: T\nflow: 10 l/s\n"), nullptr);
  ASSERT_NE(rig.add("level_switch", "High", "tank: T\nabove: 90 %\n"), nullptr);
  rig.setBool("V.open", true);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("High.value"); }));
  EXPECT_NEAR(seconds(rig.now), 9.001, 0.0015);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getNumber("T.level") >= 100.0 - 1e-9; }));
  EXPECT_NEAR(seconds(rig.now), 10.001, 0.0015);
  EXPECT_NEAR(rig.getNumber("T.volume"), 100.0, 1e-6);
  EXPECT_NEAR(rig.getNumber("T.level_mm"), 1000.0, 1e-6);
  rig.tick();
  EXPECT_TRUE(rig.getBool("T.overflow")) << "still filling a full tank spills";
}

// Where the valve stands in the device list does not change the result (feeds hold per tick).
TEST(Tank, StepOrderDoesNotMatter) {
  double levels[2];
  for (int order = 0; order < 2; ++order) {
    PlantRig rig;
    if (order == 1) ASSERT_NE(rig.add("valve", "V", "to: T\nflow: 6 l/min\n"), nullptr);
    ASSERT_NE(rig.add("tank", "T", "capacity: 10 l\n"), nullptr);
    if (order == 0) ASSERT_NE(rig.add("valve", "V", "to: T\nflow: 6 l/min\n"), nullptr);
    rig.tick();
    rig.setBool("V.open", true);
    for (int i = 0; i < 1000; ++i) rig.tick();
    levels[order] = rig.getNumber("T.volume");
  }
  EXPECT_DOUBLE_EQ(levels[0], levels[1]);
  EXPECT_NEAR(levels[0], 0.1 * 1.0, 1e-3);  // 0.1 l/s for the 1 s after the open tick
}

// A full tank with as much flowing out as in does not spill.
TEST(Tank, FullTankWithBalancedFlowsDoesNotOverflow) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\ninitial_level: 100 %\n"), nullptr);
  ASSERT_NE(rig.add("valve", "In", "to: T\nflow: 10 l/s\n"), nullptr);
  ASSERT_NE(rig.add("valve", "Out", "from: T\nflow: 10 l/s\n"), nullptr);
  rig.setBool("In.open", true);
  rig.setBool("Out.open", true);
  for (int i = 0; i < 100; ++i) {
    rig.tick();
    EXPECT_FALSE(rig.getBool("T.overflow"));
  }
  EXPECT_NEAR(rig.getNumber("T.level"), 100.0, 1e-9);
}

TEST(Tank, DrainStopsAtEmpty) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\ninitial_level: 50 %\n"), nullptr);
  ASSERT_NE(rig.add("pump", "P", "from: T\nflow: 5 l/s\npower: 500 W\n"), nullptr);
  ASSERT_NE(rig.add("level_switch", "Low", "tank: T\nbelow: 0 %\n"), nullptr);
  rig.tick();
  EXPECT_FALSE(rig.getBool("Low.value"));
  rig.setBool("P.run", true);
  ASSERT_TRUE(rig.tickUntil([&] { return rig.getBool("Low.value"); }));
  EXPECT_NEAR(seconds(rig.now), 10.002, 0.0015);  // run from the second tick
  for (int i = 0; i < 100; ++i) rig.tick();
  EXPECT_EQ(rig.getNumber("T.volume"), 0.0);
  EXPECT_TRUE(rig.getBool("P.running"));
}

// 100 l of water (100 kg, c = 4186 J/(kg·K)) heated with 4186 W: 0.01 K/s; the heater's energy
// (4186 W x its 100 s on) is in its totals, its period in the trace.
TEST(Heater, HeatingRateIsPowerOverMassTimesSpecificHeat) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\ninitial_level: 100 %\ninitial_temperature: 20 degC\n"), nullptr);
  ASSERT_NE(rig.add("heater", "H", "tank: T\npower: 4186 W\n"), nullptr);
  rig.tick();
  rig.setBool("H.on", true);
  for (int i = 0; i < 100; ++i) rig.tick(10 * kMs);
  EXPECT_NEAR(rig.getNumber("T.temperature"), 20 + 0.01 * 0.99, 1e-9);  // on from the second tick
  for (int i = 0; i < 9900; ++i) rig.tick(10 * kMs);
  EXPECT_NEAR(rig.getNumber("T.temperature"), 20 + 0.01 * 99.99, 1e-6);
  rig.setBool("H.on", false);
  rig.tick(10 * kMs);
  rig.finish();
  const DeviceTotals& totals = rig.trace.totals[1];
  EXPECT_NEAR(totals.energyJ, 4186.0 * 100.0, 1e-3);
  EXPECT_EQ(totals.busyNs, 100 * kS);
  ASSERT_EQ(rig.trace.activities.size(), 1u);
  EXPECT_EQ(rig.label(rig.trace.activities[0]), "Heating");
}

// Newton cooling: T = T_amb + (T0 − T_amb)·e^(−k·t/(m·c)).
TEST(Tank, HeatLossDecaysTowardsTheAmbient) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T",
                    "capacity: 10 l\ninitial_level: 100 %\ninitial_temperature: 80 degC\nambient_temperature: 20 degC\n"
                    "heat_loss: 41.86 W/K\n"),
            nullptr);
  for (int i = 0; i <= 1000; ++i) rig.tick(kS);  // 1000 s, time constant m·c/k = 10·4186/41.86 = 1000 s
  EXPECT_NEAR(rig.getNumber("T.temperature"), 20 + 60 * std::exp(-1.0), 1e-6);
}

// 50 l at 20 °C and 50 l at 80 °C in: 100 l at 50 °C.
TEST(Tank, InflowIsMixedIn) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 200 l\ninitial_level: 25 %\n"), nullptr);
  ASSERT_NE(rig.add("valve", "Hot", "to: T\nflow: 50 l/s\ninlet_temperature: 80 degC\n"), nullptr);
  rig.tick(kS);
  rig.setBool("Hot.open", true);
  rig.tick(kS);
  rig.setBool("Hot.open", false);
  rig.tick(kS);
  rig.tick(kS);
  EXPECT_NEAR(rig.getNumber("T.volume"), 100.0, 1e-9);
  EXPECT_NEAR(rig.getNumber("T.temperature"), 50.0, 1e-9);
}

// A pump between two tanks takes the source's temperature along.
TEST(Pump, MovesLiquidBetweenTanks) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "A", "capacity: 10 l\ninitial_level: 100 %\ninitial_temperature: 60 degC\n"), nullptr);
  ASSERT_NE(rig.add("tank", "B", "capacity: 20 l\n"), nullptr);
  ASSERT_NE(rig.add("pump", "P", "from: A\nto: B\nflow: 1 l/s\n"), nullptr);
  rig.setBool("P.run", true);
  for (int i = 0; i < 20; ++i) rig.tick(kS);
  EXPECT_NEAR(rig.getNumber("A.volume"), 0.0, 1e-9);
  EXPECT_NEAR(rig.getNumber("B.volume"), 10.0, 1e-9);
  EXPECT_NEAR(rig.getNumber("B.temperature"), 60.0, 1e-9);
}

// The plug travels in travel_time; the flow follows the opening; feedback at the end positions.
TEST(Valve, TravelTimeAndFeedback) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\n"), nullptr);
  ASSERT_NE(rig.add("valve", "V", "to: T\nflow: 1 l/s\ntravel_time: 2 s\n"), nullptr);
  rig.tick(100 * kMs);
  EXPECT_TRUE(rig.getBool("V.closed"));
  rig.setBool("V.open", true);
  for (int i = 0; i < 10; ++i) rig.tick(100 * kMs);  // 1 s: half open
  EXPECT_FALSE(rig.getBool("V.closed"));
  EXPECT_FALSE(rig.getBool("V.opened"));
  for (int i = 0; i < 10; ++i) rig.tick(100 * kMs);
  EXPECT_TRUE(rig.getBool("V.opened"));
  // ramp 0.05 .. 1.0 over 20 ticks of 0.1 s (each tick's flow counted over the next tick)
  EXPECT_NEAR(rig.getNumber("T.volume"), 0.1 * 1.0 * (0.05 + 0.95) / 2 * 19, 1e-9);
}

// An `above` switch at 80 % with 5 % hysteresis: on at 80 %, off only below 75 %.
TEST(LevelSwitch, Hysteresis) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 100 l\n"), nullptr);
  ASSERT_NE(rig.add("level_switch", "S", "tank: T\nabove: 80 %\nhysteresis: 5 %\n"), nullptr);
  ASSERT_NE(rig.add("level_switch", "Mm", "tank: T\nbelow: 300 mm\nhysteresis: 50 mm\n"), nullptr);
  Vessel& v = rig.world.vesselAt(rig.world.vessel("T", {}));
  auto levelAt = [&](double litres) {
    v.volumeM3 = litres * 1e-3;
    rig.tick();
  };
  levelAt(79.9);
  EXPECT_FALSE(rig.getBool("S.value"));
  levelAt(80.001);
  EXPECT_TRUE(rig.getBool("S.value"));
  levelAt(76.0);
  EXPECT_TRUE(rig.getBool("S.value"));
  levelAt(74.9);
  EXPECT_FALSE(rig.getBool("S.value"));
  levelAt(78.0);
  EXPECT_FALSE(rig.getBool("S.value"));
  // height 1 m (default): 300 mm is 30 l
  levelAt(30.0);
  EXPECT_TRUE(rig.getBool("Mm.value"));
  levelAt(34.0);
  EXPECT_TRUE(rig.getBool("Mm.value"));
  levelAt(35.1);
  EXPECT_FALSE(rig.getBool("Mm.value"));
}

// A first-order lag: 63.2 % of a step after one time constant; INT output in 0.1 °C.
TEST(TemperatureSensor, FirstOrderLagAndIntOutput) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "T", "capacity: 10 l\ninitial_level: 100 %\n"), nullptr);
  ASSERT_NE(rig.add("temperature_sensor", "TT", "tank: T\nlag: 10 s\n"), nullptr);
  ASSERT_NE(rig.add("temperature_sensor", "TI", "tank: T\noutput: int\n"), nullptr);
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.getNumber("TT.value"), 20.0);
  rig.world.vesselAt(rig.world.vessel("T", {})).temperatureC = 80.0;  // stays: no feeds, no loss
  for (int i = 0; i < 10000; ++i) rig.tick();
  EXPECT_NEAR(rig.getNumber("TT.value"), 20 + 60 * (1 - std::exp(-1.0)), 1e-9);
  EXPECT_EQ(rig.bus.type(rig.tagOf("TI.value")), ElemType::Int);
  EXPECT_EQ(rig.getNumber("TI.value"), 800);
}

struct BadEntry {
  const char* type;
  const char* yaml;
  const char* message;
};

class ProcessDeviceErrors : public ::testing::TestWithParam<BadEntry> {};

TEST_P(ProcessDeviceErrors, AreReportedAtTheirPlace) {
  PlantRig rig;
  EXPECT_EQ(rig.add(GetParam().type, "D", GetParam().yaml), nullptr);
  EXPECT_NE(rig.renderedDiags().find(GetParam().message), std::string::npos) << rig.renderedDiags();
}

INSTANTIATE_TEST_SUITE_P(
    Plant, ProcessDeviceErrors,
    ::testing::Values(
        BadEntry{"tank", "height: 2 m\n", "D.yaml:1:1: error[C010]: device 'D' needs 'capacity'"},
        BadEntry{"tank", "capacity: 0 l\n", "'capacity' must be greater than 0"},
        BadEntry{"tank", "capacity: 100 kg\n", "'capacity': '100 kg' is not a volume (e.g. 500 l)"},
        BadEntry{"tank", "capacity: 1 m3\ninitial_level: 120 %\n", "D.yaml:2:16: error[C010]: 'initial_level' must be from 0 % to 100 %"},
        BadEntry{"valve", "flow: 1 l/s\n", "needs 'from' (the tank it empties) and/or 'to' (the tank it fills)"},
        BadEntry{"valve", "to: T\nflow: 1 l\n", "'flow': '1 l' is not a volume flow (e.g. 20 l/min)"},
        BadEntry{"pump", "to: T\n", "needs 'flow'"},
        BadEntry{"heater", "power: 1 kW\n", "missing 'tank' (the name of a tank device)"},
        BadEntry{"level_switch", "tank: T\nabove: 90 %\nbelow: 10 %\n", "needs exactly one of 'above' and 'below'"},
        BadEntry{"level_switch", "tank: T\nabove: 90 kg\n",
                 "D.yaml:2:8: error[C010]: 'above': expected a level in % of the capacity (e.g. 95 %) or a height (e.g. 900 mm), found '90 kg'"},
        BadEntry{"level_switch", "tank: T\nabove: 90 %\nhysteresis: 5 mm\n", "'hysteresis' must be of the same kind as the threshold"},
        BadEntry{"temperature_sensor", "tank: T\noutput: float\n", "'output' must be real (°C) or int (0.1 °C), found 'float'"}));

// A device naming a tank that no entry defines: World keeps the name and where it was used, for
// the cell loader's error (tests/unit/cell: the loader reports it).
TEST(Vessels, UndefinedNamesAreKeptWithTheirUse) {
  PlantRig rig;
  ASSERT_NE(rig.add("tank", "Reactor", "capacity: 1 m3\n"), nullptr);
  ASSERT_NE(rig.add("valve", "V", "to: Reactr\nflow: 1 l/s\n"), nullptr);
  std::vector<uint32_t> undefined = rig.world.undefinedVessels();
  ASSERT_EQ(undefined.size(), 1u);
  const Vessel& v = rig.world.vesselAt(undefined[0]);
  EXPECT_EQ(v.name, "Reactr");
  EXPECT_EQ(v.firstUse.line, 1u);
  EXPECT_EQ(v.firstUse.col, 5u);
}

}  // namespace
}  // namespace virtcom::plant::test
