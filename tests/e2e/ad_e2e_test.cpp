// End-to-end tests of activity diagrams through the `virtcom` command: the example of
// examples/activity checks clean, prints its tables, is drawn as SVG and runs; a faulty diagram
// gives located diagnostics and exit code 1.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "csv_trace.hpp"
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

// The element ids of an .ad file as the drawing names them (`Diagram.Id`), read from its
// element lines (keyword, id).
std::set<std::string> elementIds(const std::string& adFile) {
  static const std::set<std::string> kKeywords = {"start",   "stop",     "activity",  "timer",
                                                  "counter", "or-join", "and-join", "and-split"};
  std::set<std::string> ids;
  std::istringstream in(virtcom::test::readFile(adFile));
  std::string line, diagram;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, id;
    words >> keyword >> id;
    if (keyword == "diagram") diagram = id;
    if (kKeywords.count(keyword)) ids.insert(diagram + "." + id);
  }
  return ids;
}

// The ids of the SVG's <g> elements; fails the test if the file is not well-formed XML.
std::set<std::string> svgGroupIds(const std::string& svgFile) {
  pugi::xml_document doc;
  pugi::xml_parse_result parsed = doc.load_file(svgFile.c_str());
  EXPECT_TRUE(parsed) << svgFile << ": " << parsed.description() << " at offset " << parsed.offset;
  EXPECT_STREQ(doc.document_element().name(), "svg");
  std::set<std::string> ids;
  for (pugi::xpath_node g : doc.select_nodes("//*[local-name()='g'][@id]")) ids.insert(g.node().attribute("id").value());
  return ids;
}

TEST(AdRender, SvgOfTheExampleHoldsEveryElement) {
  const std::string svg = ::testing::TempDir() + "tank.svg";
  std::string out;
  ASSERT_EQ(shell(inExample("ad render tank.ad --svg " + svg), out), 0) << out;
  std::set<std::string> ids = svgGroupIds(svg);
  std::set<std::string> expected = elementIds(kExampleDir + "/tank.ad");
  ASSERT_EQ(expected.size(), 28u);  // 9 + 9 + 10 elements in Supply, Reaction, Drain
  for (const std::string& id : expected) EXPECT_TRUE(ids.count(id)) << id << " is not in the SVG";
  for (const char* cluster : {"Supply", "Reaction", "Drain"}) EXPECT_TRUE(ids.count(cluster)) << cluster;
  EXPECT_TRUE(ids.count("Drain.arc12")) << "the last arc of Drain";
}

TEST(AdRender, OneDiagramAndItsDotText) {
  const std::string svg = ::testing::TempDir() + "reaction.svg";
  const std::string dot = ::testing::TempDir() + "reaction.dot";
  std::string out;
  ASSERT_EQ(shell(inExample("ad render tank.ad --diagram Reaction --svg " + svg + " --dot " + dot), out), 0) << out;
  std::set<std::string> ids = svgGroupIds(svg);
  EXPECT_TRUE(ids.count("Reaction.React"));
  EXPECT_FALSE(ids.count("Supply.Valve"));
  EXPECT_NE(virtcom::test::readFile(dot).find("\"Reaction.End\" -> \"Reaction.Heat\" [id=\"Reaction.arc6\", arrowhead=teenormal]"),
            std::string::npos);
}

TEST(AdRender, MistakesOnTheCommandLine) {
  std::string out;
  EXPECT_EQ(shell(inExample("ad render tank.ad --diagram Mixing --svg /dev/null"), out), 64) << out;
  EXPECT_NE(out.find("no diagram 'Mixing' (the file has: Supply, Reaction, Drain)"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell(inExample("ad render tank.ad"), out), 64) << out;
  EXPECT_NE(out.find("give --svg and/or --dot"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell("cd " + kDataDir + " && " + kExe + " ad render mistakes.ad --svg /dev/null", out), 1) << out;
  EXPECT_NE(out.find("error[A004]"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell(kExe + " ad render --help", out), 0) << out;
  EXPECT_NE(out.find("--diagram"), std::string::npos) << out;
}

// The value `signal` has at time t (its last change at or before t).
double valueAt(const std::vector<Change>& changes, double t) {
  double v = 0;
  for (const Change& c : changes)
    if (c.timeS <= t + 1e-9) v = c.value;
  return v;
}

// The periods a BOOL signal is on, as [start, end] times.
std::vector<std::pair<double, double>> onPeriods(const std::vector<Change>& changes) {
  std::vector<std::pair<double, double>> out;
  for (const Change& c : changes) {
    if (c.value != 0 && (out.empty() || out.back().second >= 0)) out.push_back({c.timeS, -1});
    else if (c.value == 0 && !out.empty() && out.back().second < 0) out.back().second = c.timeS;
  }
  return out;
}

// tank.ad as the PLC of a cell of process devices (tank-cell.yaml): three batches, each filled to
// the high level switch, reacted for the timer's 3 s with the heater on, and drained empty.
TEST(AdCells, FluidTankRunsThreeBatches) {
  const std::string csvFile = ::testing::TempDir() + "tank.csv";
  std::string out;
  ASSERT_EQ(shell(inExample("run tank-cell.yaml --csv " + csvFile), out), 0) << out;
  EXPECT_NE(out.find("completed: 'TankControl.Batches.CV >= 3' became true"), std::string::npos) << out;
  EXPECT_NE(out.find("ReactorHeater       heater          9.000"), std::string::npos) << out;
  EXPECT_NE(out.find("360000.0"), std::string::npos) << out;  // 3 x 3 s x 40 kW
  const std::string csv = virtcom::test::readFile(csvFile);
  const std::vector<Change> level = changes(csv, "Reactor.level");
  const auto supply = onPeriods(changes(csv, "SupplyValve.open"));
  const auto heating = onPeriods(changes(csv, "ReactorHeater.on"));
  const auto drain = onPeriods(changes(csv, "DrainValve.open"));
  ASSERT_EQ(supply.size(), 3u);
  ASSERT_EQ(heating.size(), 3u);
  ASSERT_EQ(drain.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    // filled to the high level switch (95 %): the valve closes the scan after it switches
    EXPECT_GE(valueAt(level, supply[i].second), 95.0) << "batch " << i;
    EXPECT_LT(valueAt(level, supply[i].second), 97.0) << "batch " << i;
    // the reaction: heater on from the end of the supply for exactly the 3 s timer
    EXPECT_NEAR(heating[i].first, supply[i].second, 1e-9) << "batch " << i;
    EXPECT_NEAR(heating[i].second - heating[i].first, 3.0, 1e-9) << "batch " << i;
    // drained when the reaction is over, down to the low level switch (1 %)
    EXPECT_NEAR(drain[i].first, heating[i].second, 1e-9) << "batch " << i;
    EXPECT_LT(valueAt(level, drain[i].second), 1.0) << "batch " << i;
    // the next batch is supplied only after the drain (NOT-IN Draining)
    if (i + 1 < 3) EXPECT_GT(supply[i + 1].first, drain[i].second) << "batch " << i;
  }
  for (double overflow : values(csv, "Reactor.overflow")) EXPECT_EQ(overflow, 0.0);
  // each batch: 40 kW for 3 s into about 95 kg of water, +0.30 K (P·t / (m·c)); the sensor
  // (1 s lag) reads a little less at the peak
  const std::vector<double> tank = values(csv, "Reactor.temperature");
  const std::vector<double> sensor = values(csv, "ReactorTemperature.value");
  const double peak = *std::max_element(tank.begin(), tank.end());
  EXPECT_NEAR(peak, 18.0 + 40e3 * 3 / (95.5 * 4186), 0.01);
  EXPECT_LT(*std::max_element(sensor.begin(), sensor.end()), peak);
  EXPECT_EQ(values(csv, "TankControl.Batches.CV").back(), 3.0);
}

// conveyor.ad as the PLC of the belt of conveyor-cell.yaml: of the lot of 12 parts, every
// defective one ends in the reject bin, every good one in the bin of its material, and the bins
// hold exactly what the belt produced; the belt stops after the lot (run-out).
TEST(AdCells, ConveyorSortsEveryPartIntoItsBin) {
  const std::string csvFile = ::testing::TempDir() + "conveyor.csv";
  std::string out;
  ASSERT_EQ(shell(inExample("run conveyor-cell.yaml --csv " + csvFile), out), 0) << out;
  EXPECT_NE(out.find("completed: 'ConveyorControl.RunOut.Q' became true"), std::string::npos) << out;
  const std::string csv = virtcom::test::readFile(csvFile);
  auto last = [&](const std::string& signal) { return values(csv, "Belt." + signal).back(); };
  const char* kinds[] = {"steel", "plastic", "bad_steel", "bad_plastic"};
  // where each kind must end: reject bin (defective), steel gate (steel), belt end (plastic)
  const char* expectedBin[] = {"steelGate", "end", "reject", "reject"};
  double produced = 0;
  for (size_t k = 0; k < 4; ++k) {
    produced += last(std::string("produced_") + kinds[k]);
    for (const char* bin : {"reject", "steelGate", "end"}) {
      const double count = last(std::string(bin) + "_" + kinds[k]);
      if (std::string(bin) == expectedBin[k])
        EXPECT_EQ(count, last(std::string("produced_") + kinds[k])) << bin << " " << kinds[k];
      else EXPECT_EQ(count, 0.0) << bin << " " << kinds[k];
    }
  }
  EXPECT_EQ(produced, 12.0);
  EXPECT_EQ(last("produced_steel"), 4.0);
  EXPECT_EQ(last("produced_plastic"), 5.0);
  EXPECT_EQ(last("produced_bad_steel") + last("produced_bad_plastic"), 3.0);
  EXPECT_EQ(values(csv, "ConveyorControl.Lot.CV").back(), 12.0);  // the PLC counted every part
  EXPECT_EQ(values(csv, "Belt.moving").back(), 0.0);               // and stopped the belt
}

}  // namespace
