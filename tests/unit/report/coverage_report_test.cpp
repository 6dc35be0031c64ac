// The coverage writers on hand-made data: lcov records, Cobertura XML, the terminal summary.
#include <gtest/gtest.h>

#include "report/coverage.hpp"

using namespace virtcom;

namespace {

CoveragePoint point(std::string pou, uint32_t line, uint32_t column, CoverageKind kind, uint64_t count,
                    uint32_t arm = 0, uint32_t arms = 0, std::string name = {}) {
  return {"src/main.st", std::move(pou), line, column, kind, arm, arms, std::move(name), count};
}

// MAIN: lines 3 (5x), 4 (IF, 5x, arms 2/3), 5 (2x), 6 (0x); Cell: a step and a transition.
CoverageData sample() {
  return CoverageData({
      point("MAIN", 3, 1, CoverageKind::Statement, 5),
      point("MAIN", 4, 1, CoverageKind::Statement, 5),
      point("MAIN", 4, 1, CoverageKind::Branch, 2, 0, 2),
      point("MAIN", 4, 1, CoverageKind::Branch, 3, 1, 2),
      point("MAIN", 5, 3, CoverageKind::Statement, 2),
      point("MAIN", 6, 3, CoverageKind::Statement, 0),
      point("MAIN", 6, 20, CoverageKind::Branch, 0, 0, 2),
      point("MAIN", 6, 20, CoverageKind::Branch, 0, 1, 2),
      point("Cell", 10, 1, CoverageKind::Step, 1, 0, 0, "Idle"),
      point("Cell", 11, 1, CoverageKind::Transition, 0, 0, 0, "Idle->Work"),
  });
}

TEST(CoverageLcov, RecordsFunctionsBranchesAndLines) {
  EXPECT_EQ(report::lcovTracefile(sample(), "t1"),
            "TN:t1\n"
            "SF:src/main.st\n"
            "FN:3,MAIN\n"
            "FN:10,Cell\n"
            "FNDA:5,MAIN\n"
            "FNDA:1,Cell\n"
            "FNF:2\n"
            "FNH:2\n"
            "BRDA:4,0,0,2\n"
            "BRDA:4,0,1,3\n"
            "BRDA:6,0,0,-\n"
            "BRDA:6,0,1,-\n"
            "BRF:4\n"
            "BRH:2\n"
            "DA:3,5\n"
            "DA:4,5\n"
            "DA:5,2\n"
            "DA:6,0\n"
            "DA:10,1\n"
            "DA:11,0\n"
            "LF:6\n"
            "LH:4\n"
            "end_of_record\n");
}

TEST(CoverageLcov, NamesStayOnOneField) {
  CoverageData d({{"a.st", "FB,x\nq", 1, 1, CoverageKind::Statement, 0, 0, {}, 1}});
  // ',' would end the field; a line break (a control character) becomes U+FFFD.
  EXPECT_NE(report::lcovTracefile(d, "my,test").find("FN:1,FB_x\xEF\xBF\xBDq\n"), std::string::npos)
      << report::lcovTracefile(d, "my,test");
  EXPECT_NE(report::lcovTracefile(d, "my,test").find("TN:my_test\n"), std::string::npos);
}

TEST(CoverageCobertura, ClassesPerPouWithBranchLines) {
  const std::string xml = report::coberturaXml(sample());
  EXPECT_NE(xml.find("<coverage line-rate=\"0.6667\" branch-rate=\"0.5000\" lines-covered=\"4\" lines-valid=\"6\" "
                     "branches-covered=\"2\" branches-valid=\"4\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<package name=\"src\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<class name=\"MAIN\" filename=\"src/main.st\" line-rate=\"0.7500\" branch-rate=\"0.5000\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<line number=\"4\" hits=\"5\" branch=\"true\" condition-coverage=\"100% (2/2)\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<line number=\"6\" hits=\"0\" branch=\"true\" condition-coverage=\"0% (0/2)\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<line number=\"3\" hits=\"5\" branch=\"false\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<class name=\"Cell\""), std::string::npos) << xml;
}

TEST(CoverageSummary, OneRowPerPouAndATotal) {
  const std::string text = report::coverageSummaryText(sample());
  EXPECT_EQ(text,
            "Coverage  lines             branches          steps             transitions\n"
            "MAIN      3/4 75.0%         2/4 50.0%         -                 -\n"
            "Cell      1/2 50.0%         -                 1/1 100.0%        0/1 0.0%\n"
            "total     4/6 66.7%         2/4 50.0%         1/1 100.0%        0/1 0.0%\n");
}

// An activity-diagram file: Lamp.Lights has rules at lines 8 (fired 7x) and 9 (never), the
// PROGRAM's call of the diagram is at line 5 (7x).
CoverageData diagram() {
  const auto at = [](std::string pou, uint32_t line, CoverageKind kind, uint64_t count, std::string name = {}) {
    return CoveragePoint{"cell/lamp.ad", std::move(pou), line, 3, kind, 0, 0, std::move(name), count};
  };
  return CoverageData({at("Lamp", 5, CoverageKind::Statement, 7), at("Lamp.Lights", 8, CoverageKind::Rule, 7, "1"),
                       at("Lamp.Lights", 9, CoverageKind::Rule, 0, "2")});
}

TEST(CoverageRules, AreLinesOfTheDiagramFile) {
  EXPECT_EQ(report::lcovTracefile(diagram(), "t"),
            "TN:t\nSF:cell/lamp.ad\nFN:5,Lamp\nFN:8,Lamp.Lights\nFNDA:7,Lamp\nFNDA:7,Lamp.Lights\nFNF:2\nFNH:2\n"
            "BRF:0\nBRH:0\nDA:5,7\nDA:8,7\nDA:9,0\nLF:3\nLH:2\nend_of_record\n");
  const std::string xml = report::coberturaXml(diagram());
  EXPECT_NE(xml.find("<class name=\"Lamp.Lights\" filename=\"cell/lamp.ad\" line-rate=\"0.5000\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<line number=\"9\" hits=\"0\" branch=\"false\"/>"), std::string::npos) << xml;
}

TEST(CoverageRules, HaveTheirColumnInTheSummaryOnlyWhenThereAreRules) {
  EXPECT_EQ(report::coverageSummaryText(diagram()),
            "Coverage     lines             branches          steps             transitions       rules\n"
            "Lamp         1/1 100.0%        -                 -                 -                 -\n"
            "Lamp.Lights  1/2 50.0%         -                 -                 -                 1/2 50.0%\n"
            "total        2/3 66.7%         -                 -                 -                 1/2 50.0%\n");
  const std::vector<report::PouCoverage> rows = report::coverageByPou(diagram());
  EXPECT_EQ(rows.back().rules.hit, 1u);
  EXPECT_EQ(rows.back().rules.total, 2u);
  EXPECT_EQ(report::coverageSummaryText(sample()).find("rules"), std::string::npos);
}

}  // namespace
