#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "example_trace.hpp"

namespace virtcom::report {
namespace {

using nlohmann::json;

json render(const Trace& t) { return json::parse(jsonReport(t, computeKpis(t))); }

TEST(JsonReport, HeaderRunAndCycle) {
  json j = render(testing::exampleCellTrace());
  EXPECT_EQ(j["schema"], "virtcom.report");
  EXPECT_EQ(j["schema_version"], kJsonSchemaVersion);
  EXPECT_EQ(j["run"]["end"], "time_limit");
  EXPECT_EQ(j["run"]["end_text"], "time limit reached");
  EXPECT_EQ(j["run"]["end_message"], "time limit of 75 s reached");
  EXPECT_DOUBLE_EQ(j["run"]["duration_s"].get<double>(), 75.0);
  EXPECT_EQ(j["run"]["cycles_completed"], 1);
  EXPECT_EQ(j["cycle"]["measured"], true);
  EXPECT_DOUBLE_EQ(j["cycle"]["start_s"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["cycle"]["end_s"].get<double>(), 73.0);
  EXPECT_DOUBLE_EQ(j["cycle"]["time_s"].get<double>(), 71.0);
}

// A paced run's late ticks and the audited external writes are in "run" only when known.
TEST(JsonReport, LateTicksAndExternalWritesWhenKnown) {
  Trace t = testing::exampleCellTrace();
  t.time.ticks = 7500;
  json plain = render(t);
  EXPECT_FALSE(plain["run"]["time"].contains("late_ticks")) << "not paced";
  EXPECT_FALSE(plain["run"].contains("external_writes")) << "not audited";
  t.time.paced = true;
  t.time.lateTicks = 3;
  t.time.maxLateNs = 12'500'000;
  t.writesAudited = true;
  t.externalWrites = {1, 2, 0, 4};
  json j = render(t);
  EXPECT_EQ(j["run"]["time"]["late_ticks"], 3);
  EXPECT_DOUBLE_EQ(j["run"]["time"]["max_late_s"].get<double>(), 0.0125);
  EXPECT_EQ(j["run"]["external_writes"], json({{"total", 7}, {"ads", 1}, {"modbus", 2}, {"opcua", 0}, {"http", 4}}));
}

TEST(JsonReport, TotalsAndDevices) {
  json j = render(testing::exampleCellTrace());
  EXPECT_NEAR(j["totals"]["energy_j"].get<double>(), 22963.05, 1e-9);
  EXPECT_EQ(j["totals"]["operations"], 18);
  EXPECT_EQ(j["totals"]["errors"], 1);
  EXPECT_EQ(j["totals"]["collisions"], 1);
  EXPECT_EQ(j["totals"]["faults"], 1);
  ASSERT_EQ(j["devices"].size(), 6u);
  const json& r2 = j["devices"][1];
  EXPECT_EQ(r2["index"], 1);
  EXPECT_EQ(r2["name"], "Robot2");
  EXPECT_EQ(r2["type"], "robot");
  EXPECT_EQ(r2["group"], "");
  EXPECT_DOUBLE_EQ(r2["busy_s"].get<double>(), 38.0);
  EXPECT_DOUBLE_EQ(r2["idle_s"].get<double>(), 33.0);
  EXPECT_DOUBLE_EQ(r2["utilisation_pct"].get<double>(), 3800.0 / 71.0);
  EXPECT_DOUBLE_EQ(r2["energy_j"].get<double>(), 12196.1);
  EXPECT_DOUBLE_EQ(r2["activity_energy_j"].get<double>(), 420 + 800 + 210 + 1200);
  EXPECT_EQ(r2["operations"], 5);
  EXPECT_EQ(r2["errors"], 1);
  EXPECT_EQ(r2["running_at_end"], 1);
}

TEST(JsonReport, ActivitiesCollisionsFaults) {
  Trace t = testing::exampleCellTrace();
  json j = render(t);
  ASSERT_EQ(j["activities"].size(), t.activities.size());
  const json& err = j["activities"][10];
  EXPECT_EQ(err["device"], "Robot2");
  EXPECT_EQ(err["device_index"], 1);
  EXPECT_EQ(err["label"], "PickBearing");
  EXPECT_DOUBLE_EQ(err["start_s"].get<double>(), 33.0);
  EXPECT_DOUBLE_EQ(err["end_s"].get<double>(), 38.0);
  EXPECT_DOUBLE_EQ(err["duration_s"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(err["energy_j"].get<double>(), 210.0);
  EXPECT_EQ(err["error"], 17);
  const json& running = j["activities"][18];
  EXPECT_TRUE(running["end_s"].is_null());
  EXPECT_DOUBLE_EQ(running["duration_s"].get<double>(), 3.0);

  ASSERT_EQ(j["collisions"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["collisions"][0]["time_s"].get<double>(), 29.0);
  EXPECT_EQ(j["collisions"][0]["zone"], "SharedZone");
  EXPECT_EQ(j["collisions"][0]["device_a"], "Robot1");
  EXPECT_EQ(j["collisions"][0]["activity_a"], "ScrewStud");
  EXPECT_EQ(j["collisions"][0]["device_b"], "Robot2");
  EXPECT_EQ(j["collisions"][0]["activity_b"], "PlaceBearing");
  ASSERT_EQ(j["faults"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["faults"][0]["time_s"].get<double>(), 38.0);
  EXPECT_EQ(j["faults"][0]["source"], "Robot2");
  EXPECT_EQ(j["faults"][0]["message"], "gripper lost the bearing (error 17)");
}

// Every cycle with its start, end and length, and their min, mean and max (issue 16).
TEST(JsonReport, EveryCycleAndTheirSpread) {
  json j = render(testing::threeCycleTrace());
  EXPECT_DOUBLE_EQ(j["cycle"]["time_s"].get<double>(), 21.0) << "the measured cycle is the last";
  EXPECT_DOUBLE_EQ(j["cycle"]["min_s"].get<double>(), 21.0);
  EXPECT_NEAR(j["cycle"]["mean_s"].get<double>(), 73.0 / 3, 1e-9);
  EXPECT_DOUBLE_EQ(j["cycle"]["max_s"].get<double>(), 30.0);
  ASSERT_EQ(j["cycle"]["cycles"].size(), 3u);
  EXPECT_DOUBLE_EQ(j["cycle"]["cycles"][1]["start_s"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(j["cycle"]["cycles"][1]["end_s"].get<double>(), 52.0);
  EXPECT_DOUBLE_EQ(j["cycle"]["cycles"][1]["time_s"].get<double>(), 22.0);
  json none = render(Trace{});
  EXPECT_EQ(none["cycle"]["cycles"].size(), 0u);
  EXPECT_DOUBLE_EQ(none["cycle"]["min_s"].get<double>(), 0.0);
}

TEST(JsonReport, KeyOrderIsFixedAndOutputDeterministic) {
  Trace t = testing::exampleCellTrace();
  std::string a = jsonReport(t, computeKpis(t));
  EXPECT_EQ(a, jsonReport(t, computeKpis(t)));
  EXPECT_EQ(a.rfind("{\n  \"schema\": \"virtcom.report\",\n  \"schema_version\": 1,", 0), 0u) << a.substr(0, 80);
  EXPECT_TRUE(a.ends_with("}\n"));
}

TEST(JsonReport, InvalidUtf8AndQuotesInNamesStayValidJson) {
  Trace t;
  t.addDevice("bad\xff\"name\"", "robot");
  t.endNs = 1;
  json j = render(t);
  EXPECT_EQ(j["devices"][0]["name"], "bad\xEF\xBF\xBD\"name\"");
}

}  // namespace
}  // namespace virtcom::report
