// Charts are exported as graphical SFC (not as the ST they are lowered to) and come back as the
// same chart: every chart of tests/golden/st/sfc, exported and imported again, has the same
// active steps scan by scan (and the golden file's CHECK-STEPS); a graphical chart imported,
// exported and imported again behaves the same with its inputs driven.
#include <pugixml.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "lang/sfc/step_monitor.hpp"
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kSfcGoldenDir = fs::path(VIRTCOM_SOURCE_DIR) / "tests" / "golden" / "st" / "sfc";

// The charts that compile (the others have a .diag file of expected errors).
std::vector<std::string> compilingCharts() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kSfcGoldenDir)) {
    fs::path p = entry.path();
    if (p.extension() == ".st" && !fs::exists(fs::path(p).replace_extension(".diag"))) names.push_back(p.filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The golden header: `// RUN: cycles=N cycle-time=10ms|250us`, `// CHECK-STEPS: scan steps...`
// and the variables the CHECK, CHECK-AT and CHECK-BITS lines watch.
struct Header {
  int cycles = 1;
  int64_t cycleNs = 10'000'000;
  std::map<int, std::string> steps;
  std::set<std::string> watched;
};

Header readHeader(const std::string& text) {
  Header h;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("// RUN:", 0) == 0) {
      size_t c = line.find("cycles="), t = line.find("cycle-time=");
      if (c != std::string::npos) h.cycles = std::stoi(line.substr(c + 7));
      if (t != std::string::npos) {
        size_t digits = 0;
        int64_t n = std::stoll(line.substr(t + 11), &digits);
        h.cycleNs = n * (line.compare(t + 11 + digits, 2, "us") == 0 ? 1'000 : 1'000'000);
      }
    } else if (line.rfind("// CHECK-STEPS: ", 0) == 0) {
      std::string rest = line.substr(16);
      size_t space = rest.find(' ');
      h.steps[std::stoi(rest.substr(0, space))] = space == std::string::npos ? "" : rest.substr(space + 1);
    } else if (line.rfind("// CHECK", 0) == 0 && line.find(" = ") != std::string::npos) {
      std::string lhs = line.substr(0, line.find(" = "));
      lhs.erase(lhs.find_last_not_of(' ') + 1);
      h.watched.insert(lhs.substr(lhs.rfind(' ') + 1));
    }
  }
  return h;
}

// The active steps after every scan, as `virtcom exec --trace-steps` prints them, and the
// values of the watched variables.
std::vector<std::string> stepTrace(bc::Module& module, const Header& header) {
  for (auto& task : module.tasks) task.intervalNs = header.cycleNs;
  std::vector<sfc::StepVariable> steps = sfc::findSteps(module);
  EXPECT_FALSE(steps.empty());
  Plc plc(module);
  std::vector<std::string> trace;
  for (int k = 0; k < header.cycles; ++k) {
    plc.scan();
    std::string active;
    sfc::formatActiveSteps(steps, plc.memory(), active);
    for (const auto& name : header.watched) active += " | " + name + " = " + plc.get(name);
    trace.push_back(active);
  }
  return trace;
}

class ChartExport : public ::testing::TestWithParam<std::string> {};

TEST_P(ChartExport, GraphicalChartRunsLikeTheTextualOne) {
  const std::string text = readFile(kSfcGoldenDir / GetParam());
  Header header = readHeader(text);
  auto original = compile({input(GetParam(), text)});
  ASSERT_NE(original->module, nullptr) << original->rendered();
  std::string xml = exportOf({input(GetParam(), text)});
  EXPECT_NE(xml.find("<SFC>"), std::string::npos) << xml;
  EXPECT_EQ(xml.find("__sfc_"), std::string::npos) << "the lowered chart leaked into the export\n" << xml;
  EXPECT_EQ(xml.find("SFC_STEP"), std::string::npos) << xml;
  auto reimported = compile({input("exported.xml", xml)});
  ASSERT_NE(reimported->module, nullptr) << reimported->rendered() << xml;
  EXPECT_EQ(exportOf({input("exported.xml", xml)}), xml) << "export of the import is a fixed point";

  std::vector<std::string> before = stepTrace(*original->module, header);
  std::vector<std::string> after = stepTrace(*reimported->module, header);
  EXPECT_EQ(after, before);
  ASSERT_FALSE(header.steps.empty() && header.watched.empty()) << "the golden file checks nothing";
  for (const auto& [scan, steps] : header.steps) {
    EXPECT_EQ(after.at(scan - 1).substr(0, after.at(scan - 1).find(" | ")), steps) << "after scan " << scan;
  }
}

INSTANTIATE_TEST_SUITE_P(GoldenCharts, ChartExport, ::testing::ValuesIn(compilingCharts()), [](const auto& info) {
  return info.param.substr(0, info.param.find('.'));
});

// The structure a vendor tool draws: branches as divergences/convergences, loops as jumps,
// actions as action blocks, every connection pointing at an element of the chart.
TEST(ChartExportStructure, BranchesJumpsAndActionBlocksAreConnectedElements) {
  std::string xml = exportOf({input("branches.st", readFile(kSfcGoldenDir / "branches.st"))});
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(xml.c_str()));
  pugi::xml_node sfc = doc.select_node("//pou[@name='MAIN']/body/SFC").node();
  ASSERT_TRUE(sfc) << xml;
  std::map<std::string, int> kinds;
  std::set<std::string> ids;
  for (pugi::xml_node e : sfc.children()) {
    ++kinds[e.name()];
    EXPECT_TRUE(ids.insert(e.attribute("localId").value()).second) << "duplicate localId " << e.attribute("localId").value();
  }
  for (pugi::xpath_node c : sfc.select_nodes(".//connection"))
    EXPECT_TRUE(ids.count(c.node().attribute("refLocalId").value())) << "dangling refLocalId " << c.node().attribute("refLocalId").value();
  EXPECT_EQ(kinds["step"], 7);
  EXPECT_EQ(kinds["simultaneousDivergence"], 1);
  EXPECT_EQ(kinds["simultaneousConvergence"], 1);
  EXPECT_EQ(kinds["selectionDivergence"], 1);
  EXPECT_EQ(kinds["selectionConvergence"], 1);
  EXPECT_EQ(kinds["jumpStep"], 1) << "the convergence jumps back to Start";
  EXPECT_TRUE(doc.select_node("//pou[@name='MAIN']/transitions/transition[@name='TB_slow']")) << "a named transition with an ST body";
  EXPECT_TRUE(sfc.select_node("transition[@priority='1']/condition")) << xml;
  xml = exportOf({input("qualifiers.st", readFile(kSfcGoldenDir / "qualifiers.st"))});
  EXPECT_NE(xml.find("qualifier=\"L\" duration=\"T#"), std::string::npos) << xml;
  xml = exportOf({input("indicators.st", readFile(kSfcGoldenDir / "indicators.st"))});
  EXPECT_NE(xml.find("qualifier=\"N\" indicator=\"full\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("qualifier=\"L\" duration=\"T#20ms\" indicator=\"lampOn\""), std::string::npos) << xml;
}

// beremiz_sfc.xml: priorities, a parallel branch, jumps, action blocks with a POU action, an
// inline action and a stored BOOL; the inputs drive every path.
TEST(ChartExportGraphical, ImportedChartBehavesTheSameAfterExportAndImport) {
  std::string xml = exportOf({input("beremiz_sfc.xml", readFile(kGoldenDir / "beremiz_sfc.xml"))});
  EXPECT_NE(xml.find("<SFC>"), std::string::npos) << xml;
  auto original = compileGolden("beremiz_sfc.xml");
  auto reimported = compile({input("exported.xml", xml)});
  ASSERT_NE(original->module, nullptr) << original->rendered();
  ASSERT_NE(reimported->module, nullptr) << reimported->rendered() << xml;
  EXPECT_EQ(exportOf({input("exported.xml", xml)}), xml);
  Plc a(*original->module), b(*reimported->module);
  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"CELL.start", "TRUE"}, {"CELL.start", "FALSE"}, {"CELL.done2", "TRUE"}, {"CELL.done2", "FALSE"},
      {"CELL.abort", "TRUE"}, {"CELL.start", "TRUE"}, {"CELL.abort", "FALSE"}, {"CELL.reset", "TRUE"}};
  for (const auto& [name, value] : inputs) {
    a.set(name, value);
    b.set(name, value);
    for (int k = 0; k < 2; ++k) {
      a.scan();
      b.scan();
      for (const char* v : {"CELL.Init.X", "CELL.Step2_1.X", "CELL.Step2_2.X", "CELL.Aborted.X", "CELL.fills", "CELL.pulses", "CELL.alarm"})
        EXPECT_EQ(a.get(v), b.get(v)) << v << " after " << name << " := " << value;
    }
  }
}

}  // namespace
}  // namespace virtcom::plcopen::testing
