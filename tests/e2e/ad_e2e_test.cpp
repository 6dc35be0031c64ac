// End-to-end tests of activity diagrams through the `virtcom` command: the example of
// examples/activity checks clean, prints its tables and runs; a faulty diagram gives located
// diagnostics and exit code 1.
#include <gtest/gtest.h>

#include <string>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::shell;

const std::string kExe = VIRTCOM_EXE;
const std::string kExampleDir = VIRTCOM_SOURCE_DIR "/examples/activity";
const std::string kDataDir = VIRTCOM_SOURCE_DIR "/tests/e2e/data/ad";

std::string inExample(const std::string& args) { return "cd " + kExampleDir + " && " + kExe + " " + args; }

TEST(AdCli, ExampleChecksClean) {
  std::string out;
  EXPECT_EQ(shell(inExample("check tank.ad"), out), 0) << out;
  EXPECT_NE(out.find("ok: 1 file(s), no diagnostics"), std::string::npos) << out;
}

TEST(AdCli, TablesOfTheExampleMatchItsTablesFile) {
  std::string out;
  ASSERT_EQ(shell(inExample("ad tables tank.ad"), out), 0) << out;
  EXPECT_EQ(out, virtcom::test::readFile(kExampleDir + "/tank.tables"));
}

TEST(AdCli, TablesAsMarkdownAndCsv) {
  std::string out;
  ASSERT_EQ(shell(inExample("ad tables tank.ad --format markdown"), out), 0) << out;
  EXPECT_NE(out.find("| 1 | 2 | Start=on AND Full=off AND Busy=off | Valve=on |"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(inExample("ad tables tank.ad --format csv"), out), 0) << out;
  EXPECT_NE(out.find("Supply,1,2,Start=on AND Full=off AND Busy=off,Valve=on"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell(inExample("ad tables tank.ad --format html"), out), 64) << out;
}

// With the operator's start held, tank.ad and its plant model (plant.st) cycle through supply
// (50 scans), the 3 s reaction and drainage: 12 s of 10 ms scans finish three batches, and the
// fourth is reacting.
TEST(AdCli, ExampleRunsBatchesAgainstItsPlant) {
  std::string out;
  ASSERT_EQ(shell(inExample("exec tank.ad plant.st --cycles 1200 --set TankControl.StartButton=TRUE "
                            "--print TankControl.Batches.CV --print TankControl.Batches.Q "
                            "--print TankControl.Heater --print TankPlant.Level"),
                  out),
            0)
      << out;
  EXPECT_EQ(out,
            "TankControl.Batches.CV = 3\nTankControl.Batches.Q = TRUE\nTankControl.Heater = TRUE\n"
            "TankPlant.Level = 100\n");
}

// The reaction holds the heater on for exactly the timer's 3 s: from scan 50 to scan 350.
TEST(AdCli, ReactionTimeIsHeld) {
  std::string out;
  ASSERT_EQ(shell(inExample("exec tank.ad plant.st --cycles 400 --set TankControl.StartButton=TRUE "
                            "--trace TankControl.Heater"),
                  out),
            0)
      << out;
  EXPECT_NE(out.find("49,490,FALSE\n50,500,TRUE\n"), std::string::npos) << out.substr(0, 2000);
  EXPECT_NE(out.find("349,3490,TRUE\n350,3500,FALSE\n"), std::string::npos);
}

TEST(AdCli, FaultyDiagramIsReportedWithItsLocation) {
  std::string out;
  EXPECT_EQ(shell("cd " + kDataDir + " && " + kExe + " check mistakes.ad", out), 1) << out;
  EXPECT_NE(out.find("mistakes.ad:12:13: error[A004]: the arc names 'Lamp2'"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell("cd " + kDataDir + " && " + kExe + " ad tables mistakes.ad", out), 1) << out;
  EXPECT_NE(out.find("error[A004]"), std::string::npos) << out;
}

}  // namespace
