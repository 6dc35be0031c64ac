// End-to-end tests of the activity-diagram file commands: `ad convert` (.ad <-> AD-XML), the
// AD-XML form in every command, `ad export` (ST and PLCopen LD) run as programs, and
// `exec --trace-rules`.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::shell;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kExampleDir = VIRTCOM_SOURCE_DIR "/examples/activity";

std::string inExample(const std::string& args) { return "cd " + kExampleDir + " && " + kExe + " " + args; }
std::string temp(const std::string& name) { return ::testing::TempDir() + "virtcom_adx_" + name; }

// Three batches in 12 s with the start held (as ExampleRunsBatchesAgainstItsPlant in ad_e2e_test.cpp).
const std::string kBatchRun = " plant.st --cycles 1200 --set TankControl.StartButton=TRUE "
                              "--print TankControl.Batches.CV --print TankControl.Heater --print TankPlant.Level";
const std::string kBatchResult = "TankControl.Batches.CV = 3\nTankControl.Heater = TRUE\nTankPlant.Level = 100\n";

TEST(AdConvert, TextToXmlAndBackKeepsTablesAndBehaviour) {
  std::string out;
  ASSERT_EQ(shell(inExample("ad convert tank.ad --xml " + temp("tank.adxml")), out), 0) << out;
  EXPECT_NE(readFile(temp("tank.adxml")).find("<arc from=\"Full\" to=\"Open\" kind=\"NOT-IN\" />"), std::string::npos);
  ASSERT_EQ(shell(inExample("ad convert " + temp("tank.adxml") + " --ad " + temp("tank.ad")), out), 0) << out;
  for (const std::string& file : {temp("tank.adxml"), temp("tank.ad")}) {
    out.clear();
    ASSERT_EQ(shell(inExample("ad tables " + file), out), 0) << out;
    EXPECT_EQ(out, readFile(kExampleDir + "/tank.tables")) << file;
    out.clear();
    ASSERT_EQ(shell(inExample("exec " + file + kBatchRun), out), 0) << out;
    EXPECT_EQ(out, kBatchResult) << file;
  }
}

TEST(AdConvert, NeedsExactlyOneOutput) {
  std::string out;
  EXPECT_EQ(shell(inExample("ad convert tank.ad"), out), 64) << out;
  EXPECT_NE(out.find("give exactly one of --xml OUT.adxml and --ad OUT.ad"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(kExe + " ad convert --help", out), 0) << out;
  EXPECT_NE(out.find("--xml"), std::string::npos) << out;
}

TEST(AdConvert, MistakesInTheXmlAreLocated) {
  std::ofstream(temp("bad.adxml")) << "<program name=\"P\">\n  <port name=\"A\" kind=\"I\"/>\n  <diagram name=\"D\">\n"
                                      "    <start id=\"S\"/>\n    <activity id=\"A\"/>\n    <arc from=\"S\" to=\"A\"/>\n"
                                      "    <arc from=\"A\" to=\"Lamp\"/>\n  </diagram>\n</program>\n";
  std::string out;
  EXPECT_EQ(shell(kExe + " check " + temp("bad.adxml"), out), 1) << out;
  EXPECT_NE(out.find("bad.adxml:7:23: error[A004]: the arc names 'Lamp', which diagram 'D' does not declare"),
            std::string::npos)
      << out;
}

TEST(AdExport, StAndPlcopenLadderRunAsTheDiagram) {
  std::string out;
  ASSERT_EQ(shell(inExample("ad export tank.ad --st " + temp("tank.st") + " --plcopen " + temp("tank.xml")), out), 0) << out;
  EXPECT_NE(readFile(temp("tank.st")).find("ACTION Supply:"), std::string::npos);
  EXPECT_NE(readFile(temp("tank.xml")).find("<LD>"), std::string::npos);
  for (const std::string& file : {temp("tank.st"), temp("tank.xml")}) {
    out.clear();
    ASSERT_EQ(shell(inExample("exec " + file + kBatchRun), out), 0) << out;
    EXPECT_EQ(out, kBatchResult) << file;
  }
}

TEST(AdExport, OptionsHaveHelp) {
  for (const char* command : {" ad export --help", " exec --help", " run --help"}) {
    std::string out;
    ASSERT_EQ(shell(kExe + command, out), 0) << out;
    const char* option = std::string(command) == " ad export --help" ? "--plcopen" : "--trace-rules";
    EXPECT_NE(out.find(option), std::string::npos) << command << "\n" << out;
  }
}

TEST(AdExport, NeedsAnOutput) {
  std::string out;
  EXPECT_EQ(shell(inExample("ad export tank.ad"), out), 64) << out;
  EXPECT_NE(out.find("give --st OUT.st and/or --plcopen OUT.xml"), std::string::npos) << out;
}

// Supply fills for 50 scans (rule 1 holds the valve open), then at the high level rule 2 closes
// it and marks the tank filled, and Reaction's rule 1 starts heating in the same scan.
TEST(AdTraceRules, PrintsTheRulesThatFiredEveryScan) {
  std::string out;
  ASSERT_EQ(shell(inExample("exec tank.ad plant.st --cycles 52 --set TankControl.StartButton=TRUE --trace-rules"), out), 0)
      << out;
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "scan 0  Supply rule 1 fired: SupplyValve := TRUE\n");
  EXPECT_NE(out.find("scan 49  Supply rule 1 fired: SupplyValve := TRUE\n"
                     "scan 50  Supply rule 2 fired: SupplyValve := FALSE, Filled := TRUE\n"
                     "scan 50  Reaction rule 1 fired: Heater := TRUE, React.IN := TRUE\n"
                     "scan 51  Supply rule 2 fired: SupplyValve := FALSE, Filled := TRUE\n"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("Drain"), std::string::npos) << "Drain's rules do not fire before the reaction ends";
}

// The same tank in a cell (with an idle clamp, as a cell needs a device): `run --trace-rules`
// prints the rules after every PLC tick as exec does.
TEST(AdTraceRules, RunPrintsTheRulesOfTheCellsDiagrams) {
  std::ofstream(temp("idle.st")) << "PROGRAM Idle\nVAR cmd : INT; exec, done : BOOL; END_VAR\nEND_PROGRAM\n";
  std::ofstream(temp("cell.yaml")) << "name: tank\nplc:\n  sources: [" << kExampleDir << "/tank.ad, " << kExampleDir
                                   << "/plant.st, " << temp("idle.st") << "]\n  cycle_time: 10 ms\nrun:\n  time_limit: 0.52 s\n"
                                   << "devices:\n  - name: Clamp\n    type: timed\n    commands:\n"
                                   << "      1: { name: Close, duration: 1 s }\n"
                                   << "    wiring: { programNumber: Idle.cmd, execute: Idle.exec, done: Idle.done }\n";
  std::string out;
  ASSERT_EQ(shell(kExe + " run " + temp("cell.yaml") + " --quiet --set TankControl.StartButton=TRUE --trace-rules", out), 3)
      << out;  // 3: the time limit ended the run
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "scan 0  Supply rule 1 fired: SupplyValve := TRUE\n");
  EXPECT_NE(out.find("scan 50  Supply rule 2 fired: SupplyValve := FALSE, Filled := TRUE\n"
                     "scan 50  Reaction rule 1 fired: Heater := TRUE, React.IN := TRUE\n"),
            std::string::npos)
      << out;
}

TEST(AdTraceRules, NeedsADiagram) {
  std::ofstream(temp("main.st")) << "PROGRAM MAIN\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n";
  std::string out;
  EXPECT_EQ(shell(kExe + " exec " + temp("main.st") + " --cycles 1 --trace-rules", out), 64) << out;
  EXPECT_NE(out.find("--trace-rules: no activity-diagram file (.ad, .adxml) among the PLC sources"), std::string::npos) << out;
}

}  // namespace
