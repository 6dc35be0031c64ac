// End-to-end tests of activity diagrams in reports: `ad tables --format html` (a page of its
// own, compared with a golden file) and the rule tables with per-rule firing counts in the
// reports of `virtcom run` (--json counted exactly on a diagram whose firings are known, the
// same on both backends; --report; the tank example's end-of-drain rule once per batch).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <string>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::shell;
using virtcom::test::readFile;
using Json = nlohmann::json;

const std::string kExe = VIRTCOM_EXE;
const std::string kExampleDir = VIRTCOM_SOURCE_DIR "/examples/activity";
const std::string kDataDir = VIRTCOM_SOURCE_DIR "/tests/e2e/data/ad";

std::string temp(const std::string& name) { return ::testing::TempDir() + "virtcom_adr_" + name; }

// Compares with the golden file; VIRTCOM_UPDATE_GOLDEN=1 rewrites it for review in the diff.
void expectGolden(const std::string& actual, const std::string& file) {
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) std::ofstream(file, std::ios::binary) << actual;
  EXPECT_EQ(actual, readFile(file)) << "differs from " << file << " (VIRTCOM_UPDATE_GOLDEN=1 rewrites it)";
}

TEST(AdTablesHtml, TankTablesPageMatchesGolden) {
  std::string out;
  ASSERT_EQ(shell("cd " + kExampleDir + " && " + kExe + " ad tables tank.ad --format html", out), 0) << out;
  EXPECT_TRUE(out.starts_with("<!DOCTYPE html>")) << out.substr(0, 200);
  expectGolden(out, kDataDir + "/tank.tables.html");
}

TEST(AdTablesHtml, UnknownFormatIsAUsageError) {
  std::string out;
  EXPECT_EQ(shell("cd " + kExampleDir + " && " + kExe + " ad tables tank.ad --format pdf", out), 64) << out;
  EXPECT_NE(out.find("unknown format 'pdf' (text, markdown, csv, html)"), std::string::npos) << out;
}

// The rule table of `diagram` in a run's JSON report.
const Json& ruleTable(const Json& report, const std::string& diagram) {
  for (const Json& d : report.at("diagrams"))
    if (d.at("diagram") == diagram) return d.at("rule_table");
  ADD_FAILURE() << "no diagram " << diagram;
  static const Json kNone = Json::array();
  return kNone;
}

// The counted cells end at their time limit: exit code 3 (cli/exit_codes.def, RunStopped).
constexpr int kTimeLimit = 3;

Json runJson(const std::string& cellDir, const std::string& cell, const std::string& extra, const std::string& name,
             int expectedExit = 0) {
  std::string out;
  const std::string json = temp(name + ".json");
  int code = shell("cd " + cellDir + " && " + kExe + " run " + cell + " --quiet --json " + json + extra, out);
  EXPECT_EQ(code, expectedExit) << out;
  return code == expectedExit ? Json::parse(readFile(json)) : Json::object();
}

class CountedRules : public ::testing::TestWithParam<std::string> {};

// counted.ad: rule 1 drives the 500 ms timer from scan 0 to scan 50, rule 2 sets Done in scan 50,
// the Spare diagram's rule never fires.
TEST_P(CountedRules, JsonCountsEveryScanInWhichARuleFired) {
  Json report = runJson(kDataDir, "counted-cell.yaml", " --backend " + GetParam(), "counted_" + GetParam(), kTimeLimit);
  ASSERT_TRUE(report.contains("diagrams")) << report.dump(2);
  const Json& count = ruleTable(report, "Count");
  ASSERT_EQ(count.size(), 2u) << count.dump(2);
  EXPECT_EQ(count[0].at("fired_scans"), 51) << count.dump(2);
  EXPECT_DOUBLE_EQ(count[0].at("first_fired_s").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(count[0].at("last_fired_s").get<double>(), 0.5);
  EXPECT_EQ(count[1].at("fired_scans"), 1);
  EXPECT_DOUBLE_EQ(count[1].at("first_fired_s").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(count[1].at("last_fired_s").get<double>(), 0.5);
  EXPECT_EQ(count[1].at("then"), "Finished=on");
  const Json& spare = ruleTable(report, "Spare");
  ASSERT_EQ(spare.size(), 1u);
  EXPECT_EQ(spare[0].at("fired_scans"), 0);
  EXPECT_TRUE(spare[0].at("first_fired_s").is_null());
  const Json& units = report.at("diagrams").at(0).at("lu_table");
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].at("transition"), "NOT-IN");
}

INSTANTIATE_TEST_SUITE_P(Backends, CountedRules, ::testing::Values("interp", "aot"));

// Instance `c` of counted.ad's PROGRAM in a 20 ms task beside a 10 ms one: counted in its own
// scans (0, 20, ..., 500 ms), not in every tick of the scheduler.
TEST(AdRunReport, RulesAreCountedInTheScansOfTheirOwnTask) {
  Json report = runJson(kDataDir, "counted-slow-cell.yaml", "", "counted_slow", kTimeLimit);
  const Json& count = ruleTable(report, "Count");
  ASSERT_EQ(count.size(), 2u) << report.dump(2);
  EXPECT_EQ(count[0].at("fired_scans"), 26) << count.dump(2);
  EXPECT_DOUBLE_EQ(count[0].at("last_fired_s").get<double>(), 0.5);
  EXPECT_EQ(count[1].at("fired_scans"), 1);
  EXPECT_DOUBLE_EQ(count[1].at("first_fired_s").get<double>(), 0.5);
}

TEST(AdRunReport, HtmlShowsTheRuleTablesWithTheirFirings) {
  std::string out;
  const std::string html = temp("counted.html");
  ASSERT_EQ(shell("cd " + kDataDir + " && " + kExe + " run counted-cell.yaml --quiet --report " + html, out), kTimeLimit) << out;
  std::string page = readFile(html);
  EXPECT_NE(page.find("<h2>Counted \u00b7 Count"), std::string::npos);
  EXPECT_NE(page.find("<th>fired (scans)</th><th>first s</th><th>last s</th>"), std::string::npos);
  EXPECT_NE(page.find("<td>51</td><td>0.000</td><td>0.500</td>"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"code\">Finished=on</td><td>1</td><td>0.500</td><td>0.500</td>"), std::string::npos);
}

TEST(AdRunReport, ReportsWithoutDiagramsHaveNoDiagramSection) {
  Json report = runJson(VIRTCOM_SOURCE_DIR "/examples/gearbox-cell", "cell.yaml", "", "gearbox");
  EXPECT_FALSE(report.contains("diagrams"));
}

// The tank's end-of-drain rule (Drain rule 2) holds in exactly one scan per batch: three.
TEST(AdRunReport, TankExampleCountsOneEndOfDrainPerBatch) {
  Json report = runJson(kExampleDir, "tank-cell.yaml", "", "tank");
  const Json& drain = ruleTable(report, "Drain");
  ASSERT_EQ(drain.size(), 2u);
  EXPECT_EQ(drain[1].at("fired_scans"), 3) << drain.dump(2);
  EXPECT_EQ(report.at("diagrams").size(), 3u);
  for (const Json& d : report.at("diagrams"))
    for (const Json& rule : d.at("rule_table")) EXPECT_GT(rule.at("fired_scans").get<int>(), 0) << d.at("diagram") << " " << rule.dump();
}

// The conveyor's push-done rules (rule 3: the part has passed the pusher) hold in one scan per
// part pushed: the 3 defective parts into the reject bin, the 4 good steel parts to the steel bin.
TEST(AdRunReport, ConveyorExampleCountsOnePushPerPart) {
  Json report = runJson(kExampleDir, "conveyor-cell.yaml", "", "conveyor");
  ASSERT_EQ(ruleTable(report, "Removal").size(), 3u);
  EXPECT_EQ(ruleTable(report, "Removal")[2].at("fired_scans"), 3);
  ASSERT_EQ(ruleTable(report, "Sorting").size(), 3u);
  EXPECT_EQ(ruleTable(report, "Sorting")[2].at("fired_scans"), 4);
}

}  // namespace
