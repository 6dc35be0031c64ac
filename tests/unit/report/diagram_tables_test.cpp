// The activity-diagram tables in reports (report/diagram_tables.hpp): the HTML section with and
// without rule firings (golden file), escaping, the standalone page, and the "diagrams" key of the
// JSON report.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "report/diagram_tables.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "example_trace.hpp"
#include "golden_file.hpp"

namespace virtcom::report {
namespace {

// Two rules of a diagram, as lang/ad's tables give them, the first fired in 51 scans.
DiagramTablesSection countSection(bool withFirings) {
  DiagramTablesSection s{"Counted", "Count",
                         {"LU table", {"index", "input activity", "transition", "output activity"},
                          {{"1", "Idle", "NOT-IN", "Wait"}, {"2", "Wait", "normal", "Finished"}}},
                         {"Rule table", {"index", "LU type", "IF", "THEN"},
                          {{"1", "3", "Idle=off", "Wait.IN=on"}, {"2", "1", "Wait=on", "Finished=on"}}},
                         {}};
  if (withFirings) s.firings = {{51, 0, 500'000'000}, {0, -1, -1}};
  return s;
}

TEST(DiagramTablesHtml, SectionWithFiringsMatchesGolden) {
  testing::expectGolden("diagram_tables.html", diagramTablesHtml({countSection(true)}));
}

TEST(DiagramTablesHtml, WithoutARunThereAreNoFiringColumns) {
  std::string html = diagramTablesHtml({countSection(false)});
  EXPECT_EQ(html.find("fired (scans)"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"code\">Wait.IN=on</td></tr>"), std::string::npos) << html;
  EXPECT_EQ(diagramTablesHtml({}), "");
}

TEST(DiagramTablesHtml, CellsAndNamesAreEscaped) {
  DiagramTablesSection s = countSection(false);
  s.diagram = "<b>";
  s.rules.rows[0][2] = "A=on & B=off";
  std::string html = diagramTablesHtml({s});
  EXPECT_NE(html.find("&lt;b&gt;"), std::string::npos);
  EXPECT_NE(html.find("A=on &amp; B=off"), std::string::npos);
  EXPECT_EQ(html.find("<b>"), std::string::npos);
}

TEST(DiagramTablesPage, IsACompletePageWithTheTables) {
  std::string page = diagramTablesPage("Counted", {countSection(false)});
  EXPECT_TRUE(page.starts_with("<!DOCTYPE html>\n<html lang=\"en\">")) << page.substr(0, 80);
  EXPECT_NE(page.find("<h1>Counted</h1>"), std::string::npos);
  EXPECT_NE(page.find(diagramTablesHtml({countSection(false)})), std::string::npos);
  EXPECT_TRUE(page.ends_with("</main>\n</body>\n</html>\n"));
}

TEST(DiagramTablesHtml, RunReportShowsTheSectionOnlyWithDiagrams) {
  Trace t = testing::exampleCellTrace();
  HtmlOptions options;
  EXPECT_EQ(htmlReport(t, computeKpis(t), options).find("Rule table"), std::string::npos);
  options.diagrams = {countSection(true)};
  EXPECT_NE(htmlReport(t, computeKpis(t), options).find(diagramTablesHtml(options.diagrams)), std::string::npos);
}

TEST(DiagramTablesJson, RulesCarryTheirFiringsAndUnitsTheirColumns) {
  Trace t = testing::exampleCellTrace();
  nlohmann::json j = nlohmann::json::parse(jsonReport(t, computeKpis(t), {countSection(true)}));
  ASSERT_EQ(j["diagrams"].size(), 1u);
  const nlohmann::json& d = j["diagrams"][0];
  EXPECT_EQ(d["program"], "Counted");
  EXPECT_EQ(d["diagram"], "Count");
  EXPECT_EQ(d["lu_table"][0]["input_activity"], "Idle");
  EXPECT_EQ(d["lu_table"][0]["output_activity"], "Wait");
  EXPECT_FALSE(d["lu_table"][0].contains("fired_scans"));
  EXPECT_EQ(d["rule_table"][0]["lu_type"], "3");
  EXPECT_EQ(d["rule_table"][0]["if"], "Idle=off");
  EXPECT_EQ(d["rule_table"][0]["then"], "Wait.IN=on");
  EXPECT_EQ(d["rule_table"][0]["fired_scans"], 51);
  EXPECT_DOUBLE_EQ(d["rule_table"][0]["first_fired_s"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(d["rule_table"][0]["last_fired_s"].get<double>(), 0.5);
  EXPECT_EQ(d["rule_table"][1]["fired_scans"], 0);
  EXPECT_TRUE(d["rule_table"][1]["first_fired_s"].is_null());
  EXPECT_TRUE(d["rule_table"][1]["last_fired_s"].is_null());
  EXPECT_FALSE(nlohmann::json::parse(jsonReport(t, computeKpis(t))).contains("diagrams"));
}

}  // namespace
}  // namespace virtcom::report
