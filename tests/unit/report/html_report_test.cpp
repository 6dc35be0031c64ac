#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <set>
#include <sstream>

#include "report/html_report.hpp"
#include "report/kpis.hpp"
#include "example_trace.hpp"
#include "html_check.hpp"

namespace virtcom::report {
namespace {

using testing::kS;

std::string render(const Trace& t, HtmlOptions options = {}) {
  if (options.title.empty()) options.title = "Gearbox cell";
  return htmlReport(t, computeKpis(t), options);
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t i = s.find(what); i != std::string::npos; i = s.find(what, i + 1)) ++n;
  return n;
}

TEST(HtmlChecker, CatchesMistakes) {
  EXPECT_EQ(checkBalanced("<p><b>x</b></p>"), "");
  EXPECT_NE(checkBalanced("<p><b>x</p></b>"), "");
  EXPECT_NE(checkBalanced("<p>"), "");
  EXPECT_NE(checkBalanced("<p title=\"x>y</p>"), "");
}

TEST(HtmlReport, IsWellFormedAndSelfContained) {
  HtmlOptions o;
  o.signals = {"PLC.start", "Press.force", "Nope"};
  std::string html = render(testing::exampleCellTrace(), o);
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_TRUE(html.starts_with("<!DOCTYPE html>\n<html lang=\"en\">"));
  EXPECT_TRUE(html.ends_with("</html>\n"));
  EXPECT_NE(html.find("<title>Gearbox cell \u2014 virtcom run report</title>"), std::string::npos);
  // Nothing loaded from elsewhere, no script needed.
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org/2000/svg"));
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
}

// The writes into the PLC from outside, counted by protocol under the heading (docs/security.md);
// a run whose writes were not audited says nothing about them.
TEST(HtmlReport, SaysHowManyExternalWritesTheRunSaw) {
  Trace t = testing::exampleCellTrace();
  EXPECT_EQ(render(t).find("external writes"), std::string::npos);
  t.writesAudited = true;
  t.externalWrites = {1, 2, 0, 4};
  EXPECT_NE(render(t).find(" \u00b7 7 external writes (ads 1, modbus 2, opcua 0, http 4)</p>"), std::string::npos);
  t.externalWrites = {};
  EXPECT_NE(render(t).find(" \u00b7 0 external writes (ads 0, modbus 0, opcua 0, http 0)</p>"), std::string::npos);
}

TEST(HtmlReport, KpiSummary) {
  std::string html = render(testing::exampleCellTrace());
  EXPECT_NE(html.find(">Cycle time</div><div class=\"v\">71.00<small>s</small>"), std::string::npos);
  EXPECT_NE(html.find("1 min 11 s"), std::string::npos);
  EXPECT_NE(html.find("22\u2009963.0"), std::string::npos);          // total energy
  EXPECT_NE(html.find("Energy per robot"), std::string::npos);
  EXPECT_NE(html.find(">4\u2009871.2 J</text>"), std::string::npos);   // robot energy bars
  EXPECT_NE(html.find(">12\u2009196.1 J</text>"), std::string::npos);
  EXPECT_NE(html.find("64.8 %"), std::string::npos);                   // Robot1 utilisation
  EXPECT_NE(html.find("time limit reached"), std::string::npos);
}

TEST(HtmlReport, GanttHasEveryLaneGroupLegendEntryAndAxis) {
  Trace t = testing::exampleCellTrace();
  std::string html = render(t);
  for (const DeviceInfo& d : t.devices)
    EXPECT_NE(html.find(">" + d.name + "<title>" + d.name + " (" + d.type + ")</title></text>"), std::string::npos) << d.name;
  // Groups in order robots, press, axes, other.
  size_t robots = html.find(">Robots</text>"), press = html.find(">Press</text>"),
         axes = html.find(">Axes</text>"), other = html.find(">Other</text>");
  ASSERT_NE(other, std::string::npos);
  EXPECT_LT(robots, press);
  EXPECT_LT(press, axes);
  EXPECT_LT(axes, other);
  for (const char* label : {"Feed", "LockInsert", "MoveX", "MoveY", "PickBearing", "PlaceBearing", "PressFit",
                            "ScrewStud", "UnlockInsert"})
    EXPECT_NE(html.find("></span>" + std::string(label) + "</li>"), std::string::npos) << label;
  EXPECT_EQ(html.find("></span>SharedZone</li>"), std::string::npos);  // a zone, not an operation
  EXPECT_NE(html.find("ended in error</li>"), std::string::npos);
  EXPECT_NE(html.find("measured cycle</li>"), std::string::npos);
  // Axis ticks every 10 s up to 70 and its title.
  EXPECT_NE(html.find("text-anchor=\"middle\">70</text>"), std::string::npos);
  EXPECT_NE(html.find(">time [s]</text>"), std::string::npos);
  EXPECT_NE(html.find("Cycle time 71.000 s"), std::string::npos);
  EXPECT_EQ(count(html, "<rect class=\"bar"), t.activities.size());
}

TEST(HtmlReport, ColoursAreConsistentPerLabel) {
  std::string html = render(testing::exampleCellTrace());
  // Feed sorts first and takes the first palette colour, in the legend and on both its bars.
  EXPECT_NE(html.find("<span class=\"sw\" style=\"background:#4e79a7\"></span>Feed</li>"), std::string::npos);
  EXPECT_EQ(count(html, "fill=\"#4e79a7\"><title>Feeder \u00b7 Feed"), 2u);
}

TEST(HtmlReport, ErrorsCollisionsAndFaultsAreMarked) {
  std::string html = render(testing::exampleCellTrace());
  EXPECT_EQ(count(html, "<rect class=\"bar err\""), 1u);
  EXPECT_NE(html.find("error code 17"), std::string::npos);
  EXPECT_EQ(count(html, "<rect class=\"bar run\""), 1u);
  EXPECT_EQ(count(html, "<line class=\"collision\""), 1u);
  EXPECT_NE(html.find(">Collision SharedZone: Robot1 \u2194 Robot2<title>"), std::string::npos);
  EXPECT_EQ(count(html, "<circle class=\"collision-dot\""), 2u);
  EXPECT_EQ(count(html, "<line class=\"fault\""), 1u);
  EXPECT_EQ(count(html, "<path class=\"fault-dot\""), 1u);
  EXPECT_NE(html.find("gripper lost the bearing (error 17)"), std::string::npos);
  EXPECT_NE(html.find("<g class=\"cycle\"><rect"), std::string::npos);
}

TEST(HtmlReport, EscapesNamesFromUserFiles) {
  Trace t = testing::exampleCellTrace();
  t.devices[0].name = "<script>alert(1)</script>";
  t.labels[t.activities[1].label] = "Pick & \"Place\"";
  t.faults[0].message = "</td><b>";
  HtmlOptions o;
  o.title = "Cell <b>1</b>";
  std::string html = render(t, o);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<b>1"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("Pick &amp; &quot;Place&quot;"), std::string::npos);
  EXPECT_NE(html.find("&lt;/td&gt;&lt;b&gt;"), std::string::npos);
  EXPECT_EQ(checkBalanced(html), "");
}

TEST(HtmlReport, SignalTimeline) {
  HtmlOptions o;
  o.signals = {"PLC.start", "Press.force", "Robot2.error", "Cell.recipe", "Missing"};
  std::string html = render(testing::exampleCellTrace(), o);
  EXPECT_EQ(count(html, "<polyline class=\"wave bool\""), 1u);
  EXPECT_EQ(count(html, "<polyline class=\"wave\""), 2u);
  // PLC.start: low, high at 2 s, low at 2.5 s (x = 190 + t/75 s * 982 px).
  EXPECT_NE(html.find("<polyline class=\"wave bool\" points=\"190.0,"), std::string::npos);
  EXPECT_NE(html.find(">4000</text>"), std::string::npos);  // force range
  EXPECT_NE(html.find("Not in this trace or not plottable: Cell.recipe, Missing"), std::string::npos);
  EXPECT_EQ(render(testing::exampleCellTrace()).find("class=\"chart signals\""), std::string::npos);
}

TEST(HtmlReport, StaysSmallForLongRuns) {
  HtmlOptions o;
  o.signals = {"PLC.start", "Robot1.busy", "Press.force"};
  std::string small = render(testing::longRunTrace(1), o);
  std::string big = render(testing::longRunTrace(2000), o);  // 40k activities, 40k changes
  EXPECT_EQ(checkBalanced(big), "");
  EXPECT_LT(big.size(), 600'000u) << "long run HTML is " << big.size() << " bytes";
  EXPECT_LT(count(big, "<rect class=\"bar"), 6u * 1000u);
  EXPECT_NE(big.find("operations (merged at this zoom)"), std::string::npos);
  // Each signal lane keeps at most ~4 points per pixel column.
  size_t pos = big.find("<polyline class=\"wave");
  ASSERT_NE(pos, std::string::npos);
  size_t end = big.find("/>", pos);
  EXPECT_LT(count(big.substr(pos, end - pos), " "), 4u * 1000u);
  EXPECT_GT(big.size(), small.size() / 2);
}

TEST(HtmlReport, EmptyTraceRenders) {
  Trace t;
  std::string html = render(t);
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_NE(html.find("no devices in this trace"), std::string::npos);
  EXPECT_NE(html.find("no activities recorded"), std::string::npos);
}

TEST(HtmlReport, OverlappingActivitiesStackInTracks) {
  Trace t;
  uint32_t d = t.addDevice("R", "robot");
  testing::activity(t, d, "A", 0, 10, 0);
  testing::activity(t, d, "B", 5, 15, 0);
  t.endNs = 20 * kS;
  std::string html = render(t);
  // Two tracks of (2 * 20 + 2 - 2) / 2 = 20 px in a 52 px lane instead of one 20 px bar.
  EXPECT_EQ(count(html, "height=\"20.0\" fill="), 2u);
  std::vector<double> ys;
  for (size_t i = html.find("<rect class=\"bar"); i != std::string::npos; i = html.find("<rect class=\"bar", i + 1))
    ys.push_back(std::stod(html.substr(html.find(" y=\"", i) + 4)));
  ASSERT_EQ(ys.size(), 2u);
  EXPECT_DOUBLE_EQ(ys[1] - ys[0], 22.0);
}

TEST(HtmlReport, CycleOnlyChartsTheMeasuredWindow) {
  Trace t = testing::exampleCellTrace();
  HtmlOptions o;
  o.cycleOnly = true;
  o.signals = {"PLC.start"};
  std::string html = render(t, o);
  EXPECT_EQ(checkBalanced(html), "");
  // Only the 18 operations inside 2 s .. 73 s; the axis starts at the first tick after 2 s.
  EXPECT_EQ(count(html, "<rect class=\"bar"), computeKpis(t).operations);
  EXPECT_EQ(html.find("text-anchor=\"middle\">0</text>"), std::string::npos);
  EXPECT_NE(html.find("text-anchor=\"middle\">10</text>"), std::string::npos);
  EXPECT_EQ(count(html, "<line class=\"collision\""), 1u);
  // Bars cut by the window start at the plot's left edge.
  EXPECT_NE(html.find("<rect class=\"bar\" x=\"190.0\""), std::string::npos);
  // PLC.start went high exactly at the window start: the waveform starts high.
  const std::string prefix = "<polyline class=\"wave bool\" points=\"";
  size_t wave = html.find(prefix);
  ASSERT_NE(wave, std::string::npos);
  std::istringstream points(html.substr(wave + prefix.size(), html.find('"', wave + prefix.size()) - wave - prefix.size()));
  std::vector<double> ys;
  for (std::string xy; points >> xy;) ys.push_back(std::stod(xy.substr(xy.find(',') + 1)));
  ASSERT_GE(ys.size(), 3u);
  EXPECT_LT(ys.front(), ys.back());  // high (smaller y) first, low at the end
}

TEST(HtmlReport, ManyLabelsStillGetDistinctColours) {
  Trace t;
  uint32_t d = t.addDevice("R", "robot");
  for (int i = 0; i < 40; ++i) testing::activity(t, d, "Op" + std::to_string(100 + i), i, i + 1, 0);
  t.endNs = 40 * kS;
  std::string html = render(t);
  std::set<std::string> colours;
  for (size_t i = html.find("<span class=\"sw\" style=\"background:"); i != std::string::npos;
       i = html.find("<span class=\"sw\" style=\"background:", i + 1))
    colours.insert(html.substr(i + 36, 7));
  EXPECT_EQ(colours.size(), 40u);
}

TEST(HtmlReport, Deterministic) {
  Trace t = testing::exampleCellTrace();
  EXPECT_EQ(render(t), render(t));
}

// Issue 16, the first hour with the HTML report.
TEST(HtmlReport, SeveralCyclesGetATableAndTheCardSaysWhichCycle) {
  const std::string html = render(testing::threeCycleTrace());
  EXPECT_NE(html.find("last of 3 \u00b7 measured 52.0\u201373.0 s"), std::string::npos);
  EXPECT_NE(html.find("3 cycles \u00b7 min 21.000 s \u00b7 mean 24.333 s \u00b7 max 30.000 s"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>2</td><td>30.000</td><td>52.000</td><td>22.000</td></tr>"), std::string::npos);
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_EQ(render(testing::exampleCellTrace()).find("id=\"cycles\""), std::string::npos) << "one cycle: no table";
}

TEST(HtmlReport, LongRunsListTheFirstAndLastCycles) {
  Trace t = testing::exampleCellTrace();
  for (int64_t i = 0; i < 1000; ++i) t.cycles.push_back({i * kS, (i + 1) * kS});
  const std::string html = render(t);
  EXPECT_NE(html.find("<tr><td>100</td>"), std::string::npos);
  EXPECT_EQ(html.find("<tr><td>101</td>"), std::string::npos);
  EXPECT_NE(html.find("\u2026 800 more cycles (all of them in the JSON report)"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>901</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>1000</td>"), std::string::npos);
  EXPECT_EQ(checkBalanced(html), "");
}

TEST(HtmlReport, ChartLabelsSpeakTheSignalsType) {
  Trace t = testing::exampleCellTrace();
  const TagId status = static_cast<TagId>(t.signals.size());
  t.signals.push_back({"Drive.ZSW1", ElemType::Word, 0x0231});
  const TagId delay = static_cast<TagId>(t.signals.size());
  t.signals.push_back({"MAIN.delay", ElemType::Time, 0});
  const TagId speed = static_cast<TagId>(t.signals.size());
  t.signals.push_back({"Drive.speed", ElemType::Lreal, std::bit_cast<uint64_t>(0.0)});
  t.changes.push_back({10 * kS, status, 0xB637});
  t.changes.push_back({10 * kS, delay, 1500});
  t.changes.push_back({10 * kS, speed, std::bit_cast<uint64_t>(1124.9999999999977)});
  std::stable_sort(t.changes.begin(), t.changes.end(), [](const SignalChange& a, const SignalChange& b) { return a.timeNs < b.timeNs; });
  HtmlOptions o;
  o.signals = {"Drive.ZSW1", "MAIN.delay", "Drive.speed"};
  const std::string html = render(t, o);
  EXPECT_NE(html.find(">16#B637</text>"), std::string::npos) << "WORD in hex";
  EXPECT_NE(html.find(">16#0231</text>"), std::string::npos);
  EXPECT_NE(html.find(">T#1s500ms</text>"), std::string::npos) << "TIME as IEC text";
  EXPECT_NE(html.find(">T#0ms</text>"), std::string::npos);
  EXPECT_NE(html.find(">1125</text>"), std::string::npos) << "rounded";
  EXPECT_EQ(html.find("1124.99"), std::string::npos);
}

TEST(HtmlReport, DevicesWithoutEnergyShowNotApplicable) {
  Trace t = testing::exampleCellTrace();
  t.totals[3].energyJ = 0;  // an ideal device: no power parameters
  const std::string html = render(t);
  EXPECT_NE(html.find("no energy model: the device entry gives no power parameters\">n/a</span>"), std::string::npos);
  EXPECT_EQ(render(testing::exampleCellTrace()).find(">n/a<"), std::string::npos);
}

// A short last cycle at the right edge of the chart: its bracket label is drawn left of the
// bracket, inside the chart, not cut off at the edge.
TEST(HtmlReport, CycleLabelOfAShortCycleAtTheEdgeStaysInside) {
  Trace t = testing::exampleCellTrace();
  t.cycleStartNs = 73 * kS;
  t.cycleEndNs = 75 * kS;
  const std::string html = render(t);
  const size_t label = html.find("Cycle time 2.000 s</text>");
  ASSERT_NE(label, std::string::npos);
  const size_t anchor = html.rfind("text-anchor=\"end\">", label);
  ASSERT_NE(anchor, std::string::npos);
  EXPECT_EQ(label - anchor, std::string("text-anchor=\"end\">").size()) << html.substr(anchor, 80);
}

}  // namespace
}  // namespace virtcom::report
