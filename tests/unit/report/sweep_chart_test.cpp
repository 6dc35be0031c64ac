// The sweep page: a heat map per KPI for two parameters, the KPI over each parameter otherwise
// (a line per setting of the others), failed points marked with their reason, all self-contained.
#include <gtest/gtest.h>

#include "html_check.hpp"
#include "report/sweep_chart.hpp"

namespace virtcom::report {
namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t i = s.find(what); i != std::string::npos; i = s.find(what, i + 1)) ++n;
  return n;
}

SweepTable::Row ok(size_t point, std::vector<std::string> values, double cycle, double energy) {
  return {point, std::move(values), true, cycle, energy, "ok"};
}

// Sequence 2 or 3 over three speeds, as examples/gearbox-cell/sweep.yaml; one point collided.
SweepTable twoParameters() {
  SweepTable t;
  t.title = "sweep.yaml";
  t.parameters = {"MAIN.sequence", "Robot1.max_speed"};
  t.rows = {ok(0, {"2", "900 mm/s"}, 80.5, 22000), ok(1, {"2", "1150 mm/s"}, 74.82, 22100), ok(2, {"2", "1400 mm/s"}, 71.2, 22400),
            ok(3, {"3", "900 mm/s"}, 76.1, 21800), ok(4, {"3", "1150 mm/s"}, 70.95, 21977.1),
            {5, {"3", "1400 mm/s"}, false, 0, 0, "collision at 33.28 s: Robot1 & Robot2 <in> SharedTable"}};
  return t;
}

TEST(SweepChart, TwoParametersMakeAHeatMapPerKpiWithEveryPointAndTheFailedOneMarked) {
  const std::string html = sweepHtml(twoParameters());
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_EQ(count(html, "<svg"), 2u) << "cycle time and energy";
  EXPECT_EQ(count(html, "<rect"), 12u) << "six cells per KPI";
  EXPECT_NE(html.find(">70.950<"), std::string::npos) << "the cell's value";
  EXPECT_NE(html.find("collision at 33.28 s: Robot1 &amp; Robot2 &lt;in&gt; SharedTable"), std::string::npos) << "escaped reason";
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "nothing loaded from elsewhere";
  // The speeds ordered by their number, not as text ("1150" < "900").
  EXPECT_LT(html.find(">900 mm/s<"), html.find(">1150 mm/s<"));
}

TEST(SweepChart, OneParameterIsALineOverItsValues) {
  SweepTable t;
  t.title = "speed.yaml";
  t.parameters = {"Robot1.max_speed"};
  t.rows = {ok(0, {"1400 mm/s"}, 71.2, 22400), ok(1, {"900 mm/s"}, 80.5, 22000), ok(2, {"1150 mm/s"}, 74.82, 22100)};
  const std::string html = sweepHtml(t);
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_EQ(count(html, "<svg"), 2u);
  EXPECT_EQ(count(html, "<circle"), 6u);
  EXPECT_EQ(count(html, "fill=\"none\" stroke="), 2u) << "one line per KPI";
  EXPECT_EQ(html.find("<ul class=\"legend\">"), std::string::npos) << "a single series needs no legend";
}

TEST(SweepChart, ThreeParametersChartEachWithALinePerSettingOfTheOthers) {
  SweepTable t;
  t.title = "three.yaml";
  t.parameters = {"a", "b", "c"};
  size_t point = 0;
  for (const char* a : {"1", "2"})
    for (const char* b : {"x", "y"})
      for (const char* c : {"10", "20", "30"}) t.rows.push_back(ok(point++, {a, b, c}, 60.0 + static_cast<double>(point), 100));
  const std::string html = sweepHtml(t);
  EXPECT_EQ(checkBalanced(html), "");
  EXPECT_EQ(count(html, "<svg"), 6u) << "two KPIs over three parameters";
  EXPECT_NE(html.find("b = x, c = 10"), std::string::npos) << "a series of chart 'a' named by the others' values";
  EXPECT_EQ(count(html, "<tr>"), 13u) << "the table: a header and twelve points";
}

}  // namespace
}  // namespace virtcom::report
