// Mixed programs: a diagram drives an ST function block as a type-3 unit (`block`), and an ST
// program calls a diagram's ACTION; both against hand-written ST, scan by scan, and exported.
#include <gtest/gtest.h>

#include <random>

#include "ad_fixture.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/plcopen/exporter.hpp"
#include "lang/syntax/printer.hpp"

namespace virtcom::ad {
namespace {

using test::Side;
using test::SourceFile;
using test::start;

// A user FB: Q once IN has been on for `Scans` scans in a row.
constexpr const char* kDebounce =
    "FUNCTION_BLOCK FB_Debounce\nVAR_INPUT IN : BOOL; Scans : INT := 3; END_VAR\nVAR_OUTPUT Q : BOOL; END_VAR\n"
    "VAR count : INT; END_VAR\nIF IN THEN\n  IF count < Scans THEN count := count + 1; END_IF;\nELSE\n  count := 0;\n"
    "END_IF;\nQ := count >= Scans;\nEND_FUNCTION_BLOCK\n";

// Pins other than IN/Q: the rule drives Go, the state is Done.
constexpr const char* kLatch =
    "FUNCTION_BLOCK FB_Latch\nVAR_INPUT Go : BOOL; END_VAR\nVAR_OUTPUT Done : BOOL; END_VAR\n"
    "IF Go THEN Done := NOT Done; END_IF;\nEND_FUNCTION_BLOCK\n";

constexpr const char* kDiagram =
    "program P\nport Button I\nport Stop I\nport Toggle I\nport Motor O\nport Lamp O\n"
    "diagram Run\n  start S\n  activity Button\n  activity Stop\n  activity Toggle\n  activity Motor\n  activity Lamp\n"
    "  block Debounce FB_Debounce\n  block Flip FB_Latch Go Done\n"
    "  S -> Button\n  Button -> Debounce\n  Debounce -> Motor\n  Stop ->| Motor\n"
    "  Toggle -> Flip\n  Flip -> Lamp\n  Stop ->| Lamp\nend_diagram\n";

constexpr const char* kHandWritten =
    "PROGRAM P\nVAR Button, Stop, Toggle, Motor, Lamp : BOOL; Debounce : FB_Debounce; Flip : FB_Latch; END_VAR\n"
    "Debounce(IN := Button);\nIF Debounce.Q THEN Motor := TRUE; END_IF;\nIF Stop THEN Motor := FALSE; END_IF;\n"
    "Flip(Go := Toggle);\nIF Flip.Done THEN Lamp := TRUE; END_IF;\nIF Stop THEN Lamp := FALSE; END_IF;\nEND_PROGRAM\n";

// Runs the sides with the same random inputs; the outputs must agree after every scan.
void compareScans(std::vector<Side*> sides) {
  std::mt19937 rng(7);
  bool values[3] = {};
  const char* inputs[3] = {"Button", "Stop", "Toggle"};
  bool motorOn = false, lampOn = false;
  for (int scan = 1; scan <= 800; ++scan) {
    for (int i = 0; i < 3; ++i) {
      if (rng() % (i == 1 ? 25 : 6) == 0) values[i] = !values[i];
      for (Side* side : sides) ASSERT_NO_FATAL_FAILURE(side->write(inputs[i], values[i]));
    }
    for (Side* side : sides) ASSERT_TRUE(side->runtime->tick()) << side->runtime->faultText();
    for (const char* out : {"Motor", "Lamp", "Debounce.Q", "Flip.Done"})
      for (Side* side : sides) ASSERT_EQ(side->read(out), sides[0]->read(out)) << out << " after scan " << scan;
    motorOn = motorOn || sides[0]->read("Motor") == "TRUE";
    lampOn = lampOn || sides[0]->read("Lamp") == "TRUE";
  }
  EXPECT_TRUE(motorOn && lampOn) << "the blocks must drive the outputs for the comparison to mean something";
}

std::string fbs() { return std::string(kDebounce) + kLatch; }

TEST(Mixed, DiagramDrivesStFunctionBlocksAsHandWrittenStDoes) {
  Side diagram, st;
  ASSERT_NO_FATAL_FAILURE(start(diagram, {{"d.ad", kDiagram}, {"fbs.st", fbs()}}));
  ASSERT_NO_FATAL_FAILURE(start(st, {{"p.st", kHandWritten}, {"fbs.st", fbs()}}));
  compareScans({&diagram, &st});
}

TEST(Mixed, ExportsWithStFunctionBlocksBehaveAsTheDiagram) {
  Diagnostics diags;
  Program program = readProgram(0, kDiagram, diags);
  ASSERT_FALSE(diags.hasErrors());
  st::NodeId nextId = 0;
  st::CompilationUnit unit = lowerProgram(program, 0, nextId);
  std::string xml = plcopen::exportProject({&unit}, plcopen::ExportOptions{}, diags);
  ASSERT_FALSE(diags.hasErrors());
  EXPECT_NE(xml.find("typeName=\"FB_Latch\" instanceName=\"Flip\""), std::string::npos);
  EXPECT_NE(xml.find("formalParameter=\"Done\""), std::string::npos);
  Side diagram, st, ladder;
  ASSERT_NO_FATAL_FAILURE(start(diagram, {{"d.ad", kDiagram}, {"fbs.st", fbs()}}));
  ASSERT_NO_FATAL_FAILURE(start(st, {{"d.st", st::printPou(*unit.pous.front())}, {"fbs.st", fbs()}}));
  ASSERT_NO_FATAL_FAILURE(start(ladder, {{"d.xml", xml}, {"fbs.st", fbs()}}));
  compareScans({&diagram, &st, &ladder});
}

TEST(Mixed, StProgramCallsADiagramsAction) {
  // MAIN runs the diagram's function itself. Programs run in file order: P first (Toggle still
  // off: Flip is not toggled), then MAIN, which switches Toggle on and calls Run: one toggle.
  Side side;
  side.program = "MAIN";
  ASSERT_NO_FATAL_FAILURE(start(side, {{"d.ad", kDiagram},
                                       {"fbs.st", fbs()},
                                       {"main.st", "PROGRAM MAIN\nVAR calls : INT; END_VAR\nP.Toggle := TRUE;\nP.Run();\n"
                                                   "calls := calls + 1;\nEND_PROGRAM\n"}}));
  ASSERT_TRUE(side.runtime->tick());
  EXPECT_EQ(side.read("calls"), "1");
  side.program = "P";
  EXPECT_EQ(side.read("Flip.Done"), "TRUE");
  EXPECT_EQ(side.read("Lamp"), "TRUE") << "Run's rule 'Flip -> Lamp' ran in MAIN's call";
  EXPECT_EQ(side.read("Toggle"), "TRUE");
}

std::string codes(const std::vector<SourceFile>& files) {
  Diagnostics diags;
  test::compileFiles(files, diags);
  return test::codesAndPlaces(diags);
}

TEST(Mixed, BlockMistakesAreLocatedAtTheBlock) {
  std::string diagram = kDiagram;
  EXPECT_EQ(codes({{"d.ad", diagram}}), "E104 14:3\nE104 15:3\n") << "types no file declares";
  std::string badPin = diagram;
  badPin.replace(badPin.find("FB_Latch Go Done"), 16, "FB_Latch Go Off");
  EXPECT_EQ(codes({{"d.ad", badPin}, {"fbs.st", fbs()}}), "E212 15:3\n");
  std::string reset = diagram;
  reset.replace(reset.find("Stop ->| Lamp"), 13, "Stop ->| Flip");
  EXPECT_EQ(codes({{"d.ad", reset}, {"fbs.st", fbs()}}), "A007 22:8\n") << "a block has no reset input";
  std::string oneSided = diagram;
  oneSided.replace(oneSided.find("FB_Latch Go Done"), 16, "FB_Latch Go");
  EXPECT_EQ(codes({{"d.ad", oneSided}, {"fbs.st", fbs()}}), "A001 15:3\nA004 20:13\nA004 21:3\n")
      << "both pins or neither; the arcs then name an element that was not declared";
}

}  // namespace
}  // namespace virtcom::ad
