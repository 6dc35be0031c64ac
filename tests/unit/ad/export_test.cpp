// `virtcom ad export`: every golden diagram and the tank example, exported as ST (the lowered
// program, printed) and as a PLCopen TC6 project with LD rungs, is compiled back through the
// normal front ends and run next to the diagram with the same pseudo-random inputs; every port
// must be identical after every scan.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <set>

#include "ad_fixture.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/plcopen/exporter.hpp"
#include "lang/syntax/printer.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;
using virtcom::test::readFile;

namespace virtcom::ad {
namespace {

using test::Side;
using test::start;

std::vector<fs::path> diagramFiles() {
  std::vector<fs::path> files{fs::path(VIRTCOM_SOURCE_DIR) / "examples/activity/tank.ad"};
  for (const auto& entry : fs::directory_iterator(fs::path(VIRTCOM_SOURCE_DIR) / "tests/golden/ad"))
    if (entry.path().extension() == ".ad") files.push_back(entry.path());
  std::sort(files.begin() + 1, files.end());
  return files;
}

struct Exported {
  Program program;
  std::string st, plcopen;
};

Exported exportFile(const fs::path& path) {
  Exported out;
  Diagnostics diags;
  out.program = readProgram(0, readFile(path), diags);
  EXPECT_FALSE(diags.hasErrors());
  st::NodeId nextId = 0;
  st::CompilationUnit unit = lowerProgram(out.program, 0, nextId);
  out.st = st::printPou(*unit.pous.front());
  out.plcopen = plcopen::exportProject({&unit}, plcopen::ExportOptions{}, diags);
  EXPECT_FALSE(diags.hasErrors());
  return out;
}

class Export : public ::testing::TestWithParam<fs::path> {};

TEST_P(Export, StAndLadderBehaveAsTheDiagramAfterEveryScan) {
  Exported e = exportFile(GetParam());
  std::vector<std::string> inputs, watched;
  for (const Port& port : e.program.ports) (port.kind == PortKind::Input ? inputs : watched).push_back(port.name);
  ASSERT_FALSE(inputs.empty());
  std::set<std::string> seen;  // "Y=TRUE", "Y=FALSE": guards the comparison against outputs that never change
  for (uint32_t seed : {1u, 2u, 3u}) {
    Side diagram, st, ladder;
    for (Side* side : {&diagram, &st, &ladder}) side->program = e.program.name;
    ASSERT_NO_FATAL_FAILURE(start(diagram, "d.ad", readFile(GetParam())));
    ASSERT_NO_FATAL_FAILURE(start(st, "d.st", e.st));
    ASSERT_NO_FATAL_FAILURE(start(ladder, "d.xml", e.plcopen));
    std::mt19937 rng(seed);
    std::vector<bool> values(inputs.size());
    for (int scan = 1; scan <= 1500; ++scan) {
      // Short runs first, then long ones, so counters count up to their preset and timers elapse.
      unsigned flipOneIn = scan <= 500 ? 7 : 300;
      for (size_t i = 0; i < inputs.size(); ++i) {
        if (rng() % flipOneIn == 0) values[i] = !values[i];
        for (Side* side : {&diagram, &st, &ladder}) ASSERT_NO_FATAL_FAILURE(side->write(inputs[i], values[i]));
      }
      // Now and then an output is forced from outside, so outputs a diagram only latches on (or
      // only switches off) keep moving and every rule keeps being observed.
      for (const auto& name : watched) {
        if (rng() % 40 != 0) continue;
        bool value = rng() % 2;
        for (Side* side : {&diagram, &st, &ladder}) ASSERT_NO_FATAL_FAILURE(side->write(name, value));
      }
      for (Side* side : {&diagram, &st, &ladder}) ASSERT_TRUE(side->runtime->tick()) << side->runtime->faultText();
      for (const auto& name : watched) {
        ASSERT_EQ(st.read(name), diagram.read(name)) << name << " (ST) after scan " << scan << ", seed " << seed;
        ASSERT_EQ(ladder.read(name), diagram.read(name)) << name << " (LD) after scan " << scan << ", seed " << seed;
        seen.insert(name + "=" + diagram.read(name));
      }
    }
  }
  size_t bothValues = 0;
  for (const auto& name : watched) bothValues += seen.count(name + "=FALSE") && seen.count(name + "=TRUE");
  EXPECT_EQ(bothValues, watched.size()) << "every output must take both values for the comparison to mean something";
}

INSTANTIATE_TEST_SUITE_P(Ad, Export, ::testing::ValuesIn(diagramFiles()),
                         [](const auto& info) { return info.param.stem().string(); });

TEST(ExportLadder, OneRungPerRuleWithContactsCoilsAndBlocks) {
  Exported e = exportFile(fs::path(VIRTCOM_SOURCE_DIR) / "examples/activity/tank.ad");
  const std::string& xml = e.plcopen;
  EXPECT_NE(xml.find("<LD>"), std::string::npos);
  EXPECT_EQ(xml.find("<ST>", xml.find("<actions>")), xml.find("<ST>", xml.find("</actions>")))
      << "the actions are LD only; the program body (calls of the actions) stays ST";
  for (const char* rung : {"Rule 1", "Rule 2", "Group Empty"}) EXPECT_NE(xml.find(rung), std::string::npos) << rung;
  EXPECT_NE(xml.find("<contact localId=\"3\" height=\"20\" width=\"21\" negated=\"false\">"), std::string::npos);
  EXPECT_NE(xml.find("negated=\"true\""), std::string::npos) << "NOT-IN: normally closed contacts";
  EXPECT_NE(xml.find("storage=\"set\""), std::string::npos);
  EXPECT_NE(xml.find("storage=\"reset\""), std::string::npos) << "NOT-OUT: reset coils";
  EXPECT_NE(xml.find("typeName=\"TON\" instanceName=\"React\""), std::string::npos);
  EXPECT_NE(xml.find("typeName=\"CTU\" instanceName=\"Batches\""), std::string::npos);
  EXPECT_NE(xml.find("<expression>T#3s</expression>"), std::string::npos);
}

TEST(ExportSt, IsTheLoweredProgramPrinted) {
  Exported e = exportFile(fs::path(VIRTCOM_SOURCE_DIR) / "tests/golden/ad/type1_basic.ad");
  EXPECT_EQ(e.st.substr(0, e.st.find('\n')), "PROGRAM " + e.program.name);
  EXPECT_NE(e.st.find("ACTION " + e.program.diagrams.front().name + ":\n"), std::string::npos);
  EXPECT_NE(e.st.find("__ad_fired[1] := "), std::string::npos);
  EXPECT_NE(e.st.find("END_ACTION\n"), std::string::npos);
  EXPECT_EQ(e.st.substr(e.st.size() - 12), "END_PROGRAM\n");
}

}  // namespace
}  // namespace virtcom::ad
