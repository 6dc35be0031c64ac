// Reports of a run longer than the trace's window (docs/report.md "Long runs"): the KPIs count
// the elided middle through its aggregates, the JSON and HTML say what was elided, and a run
// inside the window reads exactly as before.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "example_trace.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"

namespace virtcom::report {
namespace {

using testing::kS;
using testing::longRunTrace;

// 200 example cycles (about 4,000 activities) without cycle markers: the window is the whole run.
Trace wholeRun(size_t window) {
  Trace t = longRunTrace(200, window);
  t.cycleStartNs = t.cycleEndNs = 0;
  return t;
}

TEST(LongRun, KpisOfTheWholeRunCountTheElidedActivities) {
  const Trace all = wholeRun(kDefaultTraceWindow), bounded = wholeRun(500);
  ASSERT_EQ(all.activities.elidedCount(), 0u);
  ASSERT_GT(bounded.activities.elidedCount(), 3000u);
  const Kpis a = computeKpis(all), b = computeKpis(bounded);
  ASSERT_EQ(a.devices.size(), b.devices.size());
  for (size_t d = 0; d < a.devices.size(); ++d) {
    EXPECT_EQ(b.devices[d].operations, a.devices[d].operations) << d;
    EXPECT_EQ(b.devices[d].errors, a.devices[d].errors) << d;
    EXPECT_DOUBLE_EQ(b.devices[d].activityEnergyJ, a.devices[d].activityEnergyJ) << d;
    // The elided span's union is added to the kept one's: they can overlap only where an activity
    // crosses one of the span's two edges (one example cycle is 75 s).
    EXPECT_GE(b.devices[d].busyNs, a.devices[d].busyNs) << d;
    EXPECT_LE(b.devices[d].busyNs, a.devices[d].busyNs + 2 * 75 * kS) << d;
  }
  EXPECT_EQ(b.operations, a.operations);
  EXPECT_EQ(b.errors, a.errors);
}

TEST(LongRun, TheJsonReportSaysWhatWasElided) {
  const Trace all = wholeRun(kDefaultTraceWindow), bounded = wholeRun(500);
  const auto shortDoc = nlohmann::json::parse(jsonReport(all, computeKpis(all)));
  EXPECT_FALSE(shortDoc.contains("activities_elided"));
  EXPECT_EQ(shortDoc["activities"].size(), all.activities.size());
  const auto doc = nlohmann::json::parse(jsonReport(bounded, computeKpis(bounded)));
  ASSERT_TRUE(doc.contains("activities_elided"));
  EXPECT_EQ(doc["activities_elided"]["count"], bounded.activities.elidedCount());
  EXPECT_EQ(doc["activities"].size() + bounded.activities.elidedCount(), bounded.activities.size());
  EXPECT_LT(doc["activities_elided"]["from_s"].get<double>(), doc["activities_elided"]["to_s"].get<double>());
  EXPECT_EQ(doc["totals"]["operations"], shortDoc["totals"]["operations"]);
}

TEST(LongRun, TheGanttChartMarksTheElidedSpan) {
  const Trace all = wholeRun(kDefaultTraceWindow), bounded = wholeRun(500);
  EXPECT_EQ(htmlReport(all, computeKpis(all), {}).find("activities elided"), std::string::npos);
  const std::string html = htmlReport(bounded, computeKpis(bounded), {});
  EXPECT_NE(html.find(std::to_string(bounded.activities.elidedCount()) + " activities elided"), std::string::npos);
  EXPECT_NE(html.find("a long run: the chart shows its first and last activities"), std::string::npos);
}

TEST(LongRun, CycleTablesShowTheKeptCyclesAndTheStatisticsOfAll) {
  Trace t;
  t.setWindow(300);
  for (int64_t c = 0; c < 1000; ++c) t.cycles.push_back({c * kS, (c + 1) * kS + (c == 500 ? 7 * kS : 0)});
  t.cyclesCompleted = 1000;
  t.cycleStartNs = t.cycles.back().startNs;
  t.cycleEndNs = t.cycles.back().endNs;
  t.endNs = 1001 * kS;
  const Kpis k = computeKpis(t);
  EXPECT_EQ(k.cycleMaxNs, 8 * kS);  // an elided cycle
  EXPECT_EQ(k.cycleMinNs, kS);
  const auto doc = nlohmann::json::parse(jsonReport(t, k));
  EXPECT_EQ(doc["cycle"]["cycles"].size(), 300u);
  EXPECT_EQ(doc["cycle"]["cycles_elided"]["count"], 700u);
  EXPECT_EQ(doc["cycle"]["cycles_elided"]["after_cycle"], 150u);
  const std::string html = htmlReport(t, k, {});
  EXPECT_NE(html.find("\u2026 800 more cycles (the middle of a long run is not kept)"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>1000</td>"), std::string::npos);
}

}  // namespace
}  // namespace virtcom::report
