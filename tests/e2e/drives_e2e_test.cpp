// End-to-end: `virtcom run` on every cell in examples/drives (make test runs them). Every cell's
// PLC program drives its drive through UNIVERSAL_AXIS and the drive's bundled mapping; the speed
// cells share one program (examples/drives/main.st) and recover from an injected fault. Checked
// on the recorded PLC variables (CSV), the drive's own signals, the JSON and the HTML report.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "csv_trace.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::test::readFile;

const std::string kExamples = std::string(VIRTCOM_SOURCE_DIR) + "/examples/drives";
constexpr double kCommandedRpm = 675.0;  // 50 % of IN_SpeedMax = 1350 rpm in main.st

struct CellRun {
  int exitCode = -1;
  std::string out, csv, json, html;
};

CellRun runCell(const std::string& cell) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("virtcom_drives_e2e_" + cell + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  CellRun r;
  const std::string cmd = std::string(VIRTCOM_EXE) + " run " + kExamples + "/" + cell + "/cell.yaml --quiet --csv " +
                          (dir / "run.csv").string() + " --json " + (dir / "run.json").string() + " --report " +
                          (dir / "run.html").string() + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n = 0;
  while (p && (n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = p ? ::pclose(p) : -1;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.csv = readFile(dir / "run.csv");
  r.json = readFile(dir / "run.json");
  r.html = readFile(dir / "run.html");
  fs::remove_all(dir);
  return r;
}

double lastValue(const std::string& csv, const std::string& signal) {
  const auto v = values(csv, signal);
  return v.empty() ? NAN : v.back();
}

double maxValue(const std::string& csv, const std::string& signal) {
  const auto v = values(csv, signal);
  return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}

double minValue(const std::string& csv, const std::string& signal) {
  const auto v = values(csv, signal);
  return v.empty() ? NAN : *std::min_element(v.begin(), v.end());
}

// examples/drives/main.st ran to the end: the commanded speed was reached both ways, as the PLC
// sees it through the block and as the drive's shaft turned; the injected fault was recovered.
void expectSpeedTest(const CellRun& r, const std::string& faultText) {
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.json.find("\"end\": \"completed\""), std::string::npos) << r.json.substr(0, 400);
  EXPECT_EQ(lastValue(r.csv, "MAIN.phase"), 3.0);
  EXPECT_NEAR(lastValue(r.csv, "MAIN.forwardRpm"), kCommandedRpm, 1.0);
  EXPECT_NEAR(lastValue(r.csv, "MAIN.backwardRpm"), -kCommandedRpm, 1.0);
  EXPECT_EQ(lastValue(r.csv, "MAIN.forwardReached"), 1.0) << "OUT_Speed_Reached and OUT_PositiveDir";
  EXPECT_EQ(lastValue(r.csv, "MAIN.backwardReached"), 1.0) << "OUT_Speed_Reached and OUT_NegativeDir";
  EXPECT_NEAR(maxValue(r.csv, "Drive1.speed"), kCommandedRpm, 1.0);
  EXPECT_NEAR(minValue(r.csv, "Drive1.speed"), -kCommandedRpm, 1.0);
  EXPECT_LT(std::abs(lastValue(r.csv, "MAIN.actualRpm")), 1.0);  // stopped as the PLC sees it ...
  EXPECT_LT(std::abs(lastValue(r.csv, "Drive1.speed")), 2.0);    // ... the shaft coasting its last rpm (pulses off)
  EXPECT_NE(lastValue(r.csv, "Drive1.position"), 0.0);          // the load moved
  EXPECT_EQ(lastValue(r.csv, "MAIN.faultsSeen"), 1.0);
  EXPECT_EQ(lastValue(r.csv, "MAIN.axis.OUT_Status"), 0x7002) << "the block ends without a fault";
  EXPECT_EQ(maxValue(r.csv, "MAIN.axis.OUT_Status"), 0x8401) << "the fault reached the PLC as drive fault";
  EXPECT_NE(r.json.find(faultText), std::string::npos);
  // The report's timeline shows the speed over time (the cell's `record:` variables).
  EXPECT_NE(r.html.find("<h2>Signals</h2>"), std::string::npos);
  EXPECT_NE(r.html.find("MAIN.actualRpm"), std::string::npos);
}

TEST(DriveExamples, G120Telegram1ThroughTheBlockReachesSpeedAndRecoversFromF07900) {
  expectSpeedTest(runCell("g120"), "\"F07900\"");
}

TEST(DriveExamples, G120Telegram352ThroughTheBlockReportsTheFaultNumber) {
  const CellRun r = runCell("g120_352");
  expectSpeedTest(r, "\"F30001\"");
  EXPECT_EQ(maxValue(r.csv, "MAIN.axis.OUT_Fault_Code"), 30001.0) << "FAULT_CODE through the mapping";
  EXPECT_EQ(lastValue(r.csv, "MAIN.axis.OUT_Fault_Code"), 0.0) << "cleared after the acknowledge";
}

TEST(DriveExamples, PowerFlex525ThroughTheBlockReachesSpeedAndRecoversFromCommLoss) {
  expectSpeedTest(runCell("pf525"), "\"F83\"");
}

TEST(DriveExamples, PowerFlex750ThroughTheBlockReachesSpeedAndRecoversFromF7) {
  expectSpeedTest(runCell("pf750"), "\"F7\"");
}

// The point of the thesis: one program and one block instance; the G120 and PF525 cells differ
// in their `devices:` (drive type and mapping), not in the PLC. Both reach the commanded speed
// (checked in the tests above; here the cells' PLC sections are compared).
TEST(DriveExamples, G120AndPowerFlex525RunTheSamePlcProgram) {
  auto plcSection = [](const std::string& cell) {
    const std::string text = readFile(kExamples + "/" + cell + "/cell.yaml");
    const size_t from = text.find("\nplc:");
    const size_t to = text.find("\ndevices:");
    return from == std::string::npos || to == std::string::npos ? std::string() : text.substr(from, to - from);
  };
  const std::string siemens = plcSection("g120");
  ASSERT_NE(siemens.find("universal_axis.st"), std::string::npos) << siemens;
  EXPECT_EQ(siemens, plcSection("pf525"));
  EXPECT_EQ(siemens, plcSection("pf750"));
  EXPECT_EQ(siemens, plcSection("g120_352"));
  const CellRun g120 = runCell("g120"), pf525 = runCell("pf525");
  ASSERT_EQ(g120.exitCode, 0) << g120.out;
  ASSERT_EQ(pf525.exitCode, 0) << pf525.out;
  EXPECT_NEAR(lastValue(g120.csv, "MAIN.forwardRpm"), lastValue(pf525.csv, "MAIN.forwardRpm"), 1.0);
  EXPECT_NEAR(lastValue(g120.csv, "MAIN.forwardRpm"), kCommandedRpm, 1.0);
}

// examples/drives/epos: reference point, absolute moves to 70000 and 10000 LU, a jog, through
// UNIVERSAL_AXIS and the telegram 111 mapping; position and speed over time in the report.
TEST(DriveExamples, EposThroughTheBlockReachesBothPositionsAndJogs) {
  const CellRun r = runCell("epos");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(lastValue(r.csv, "MAIN.step"), 4.0);
  EXPECT_NEAR(lastValue(r.csv, "MAIN.reachedFirst"), 70000, 40);   // p2544 positioning window
  EXPECT_NEAR(lastValue(r.csv, "MAIN.reachedSecond"), 10000, 40);
  EXPECT_GT(lastValue(r.csv, "MAIN.jogEnd"), 10000 + 1000) << "jog + moved forward";
  EXPECT_NEAR(maxValue(r.csv, "MAIN.axis.OUT_DriveActualPosition"), 70000, 40) << "no overshoot past the window";
  EXPECT_GT(maxValue(r.csv, "MAIN.axis.OUT_ActualSpeed_rpm"), 100.0) << "the PLC saw the axis move";
  EXPECT_NE(r.html.find("MAIN.axis.OUT_DriveActualPosition"), std::string::npos);
}

TEST(DriveExamples, WordArrayWiringRunsTheDrive) {
  const std::string cmd = std::string(VIRTCOM_EXE) + " run " + VIRTCOM_SOURCE_DIR +
                          "/tests/e2e/data/drives_word_array/cell.yaml --quiet --json /dev/stdout 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  ASSERT_EQ(::pclose(p), 0) << out;
  EXPECT_NE(out.find("'MAIN.running' became true"), std::string::npos) << out;
}

}  // namespace
