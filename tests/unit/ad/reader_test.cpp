// The .ad reader and the structural checks: every mistake is a diagnostic with its code and the
// line:col of the element or arc at fault.
#include <gtest/gtest.h>

#include "lang/ad/reader.hpp"
#include "ad_fixture.hpp"

namespace virtcom::ad {
namespace {

std::string diagnose(std::string_view text) {
  Diagnostics diags;
  readProgram(0, text, diags);
  return test::codesAndPlaces(diags);
}

// A valid diagram around `lines` (activities A, an input, and Y, an output), so each case
// shows only its mistake. The lines of `lines` are numbered from 9.
std::string withDiagram(std::string_view lines) {
  return "program P\n"
         "port A I\n"
         "port Y O\n"
         "diagram D\n"
         "  start S\n"
         "  activity A\n"
         "  activity Y\n"
         "  S -> A\n" +
         std::string(lines) + "end_diagram\n";
}

TEST(AdReader, ReadsPortsElementsAndArcs) {
  Diagnostics diags;
  Program p = readProgram(0, withDiagram("  timer T TON T#1s500ms\n  counter C CTD 7\n"
                                         "  A -> T\n  T -> C\n  C ->| Y\n  A |-> Y\n"), diags);
  ASSERT_FALSE(diags.hasErrors()) << test::codesAndPlaces(diags);
  ASSERT_EQ(p.diagrams.size(), 1u);
  const Diagram& d = p.diagrams[0];
  EXPECT_EQ(p.name, "P");
  EXPECT_EQ(p.ports.size(), 2u);
  EXPECT_EQ(p.ports[0].kind, PortKind::Input);
  ASSERT_EQ(d.nodes.size(), 5u);
  EXPECT_EQ(d.nodes[3].presetNs, 1'500'000'000);
  EXPECT_EQ(d.nodes[4].block, BlockType::CTD);
  EXPECT_EQ(d.nodes[4].presetCount, 7u);
  ASSERT_EQ(d.arcs.size(), 5u);
  EXPECT_EQ(d.arcs[3].kind, ArcKind::NotOut);
  EXPECT_EQ(d.arcs[4].kind, ArcKind::NotIn);
  EXPECT_EQ(d.arcs[4].loc.line, 14u);
  EXPECT_EQ(d.arcs[4].loc.col, 5u);
}

TEST(AdReader, SyntaxMistakes) {
  EXPECT_EQ(diagnose("port A I\n"), "A001 1:1\n");                      // no program line
  EXPECT_EQ(diagnose("program P\nprogram Q\n"), "A003 2:1\n");
  EXPECT_EQ(diagnose("program P\nport 1x I\n"), "A001 2:6\n");
  EXPECT_EQ(diagnose("program P\nwire A B\n"), "A002 2:1\n");
  EXPECT_EQ(diagnose("program P\ndiagram D\n  start S\n"), "A001 2:1\n");  // no end_diagram
  EXPECT_EQ(diagnose(withDiagram("  activity B C D\n")), "A001 9:3\n");
  EXPECT_EQ(diagnose("program P\n  start S\n"), "A001 2:3\n");            // outside a diagram
}

TEST(AdReader, NamesAndReferences) {
  EXPECT_EQ(diagnose("program P\nport A I\nport a O\n"), "A003 3:6\n");   // names are case-insensitive
  EXPECT_EQ(diagnose(withDiagram("  activity a\n")), "A003 9:12\n");
  EXPECT_EQ(diagnose(withDiagram("  timer Y2 TON T#1s\n  timer y2 TON T#1s\n")), "A003 10:9\n");
  EXPECT_EQ(diagnose(withDiagram("  counter Y CTU 1\n")), "A003 9:11\n");  // clashes with activity Y
  EXPECT_EQ(diagnose(withDiagram("  A -> Nowhere\n")), "A004 9:8\n");
}

TEST(AdReader, PortsAndBlocks) {
  EXPECT_EQ(diagnose("program P\nport A X\n"), "A013 2:8\n");
  EXPECT_EQ(diagnose("program P\nport A I %QX0.0\n"), "A013 2:10\n");
  EXPECT_EQ(diagnose(withDiagram("  timer T CTU T#1s\n")), "A012 9:11\n");
  EXPECT_EQ(diagnose(withDiagram("  timer T TON 5s\n")), "A012 9:15\n");
  EXPECT_EQ(diagnose(withDiagram("  counter C CTU 40000\n")), "A012 9:17\n");
}

TEST(AdChecks, Bars) {
  EXPECT_EQ(diagnose(withDiagram("  or-join J\n  A -> J\n")), "A005 9:3\n");
  EXPECT_EQ(diagnose(withDiagram("  and-join J\n  A -> J\n  J -> Y\n")), "A006 9:3\n");
  EXPECT_EQ(diagnose(withDiagram("  and-split K\n  A -> K\n  K -> Y\n")), "A006 9:3\n");
}

TEST(AdChecks, Transitions) {
  // NOT-IN leaves a bar; NOT-OUT enters a timer; an arc enters the start.
  EXPECT_EQ(diagnose(withDiagram("  activity Z Y\n  and-split K\n  A -> K\n  K |-> Y\n  K -> Z\n")), "A007 12:5\n");
  EXPECT_EQ(diagnose(withDiagram("  timer T TON T#1s\n  A ->| T\n")), "A007 10:5\n");
  EXPECT_EQ(diagnose(withDiagram("  A -> S\n")), "A007 9:5\n");
}

TEST(AdChecks, StartInputsAndBlockDrivers) {
  EXPECT_EQ(diagnose("program P\ndiagram D\nend_diagram\n"), "A008 2:1\n");
  EXPECT_EQ(diagnose(withDiagram("  start S2\n")), "A008 9:3\n");
  EXPECT_EQ(diagnose(withDiagram("  Y -> A\n")), "A009 9:5\n");
  EXPECT_EQ(diagnose(withDiagram("  timer T TON T#1s\n  A -> T\n  Y -> T\n")), "A011 11:5\n");
}

TEST(AdChecks, CycleWithoutMemory) {
  std::string text = "program P\nport X O\nport Y O\nport Mem M\ndiagram D\n  start S\n  activity X\n  activity Y\n"
                     "  X -> Y\n  Y -> X\nend_diagram\n";
  Diagnostics diags;
  readProgram(0, text, diags);
  ASSERT_EQ(test::codesAndPlaces(diags), "A010 9:5\n");
  EXPECT_NE(diags.all()[0].message.find("X -> Y -> X"), std::string::npos) << diags.all()[0].message;
  // The same loop through an M port is a latch, not an error.
  text.replace(text.find("activity Y"), 10, "activity Y Mem");
  EXPECT_EQ(diagnose(text), "");
}

TEST(AdReader, ActivitiesBoundToAddresses) {
  EXPECT_EQ(diagnose(withDiagram("  activity L %QW0.0\n")), "A001 9:14\n");
  EXPECT_EQ(diagnose(withDiagram("  activity L %QX0.8\n")), "A001 9:14\n");
  EXPECT_EQ(diagnose(withDiagram("  activity L %IX0.1\n  A -> L\n")), "A009 10:5\n");  // the area says input
  EXPECT_EQ(diagnose(withDiagram("  activity L %qx2.7\n  A -> L\n")), "");
}

TEST(AdCompile, AddressBoundActivityCompiles) {
  Diagnostics diags;
  auto module = test::compileText("d.ad", withDiagram("  activity L %QX2.7\n  A -> L\n"), diags);
  EXPECT_NE(module, nullptr) << test::codesAndPlaces(diags);
}

TEST(AdCompile, UnknownVariableIsReportedAtTheActivity) {
  Diagnostics diags;
  auto module = test::compileText("d.ad", withDiagram("  activity Lamp Nowhere\n  A -> Lamp\n"), diags);
  EXPECT_EQ(module, nullptr);
  ASSERT_FALSE(diags.all().empty());
  EXPECT_EQ(diags.all()[0].code, "E201");
  EXPECT_EQ(diags.all()[0].loc.line, 9u);
}

}  // namespace
}  // namespace virtcom::ad
