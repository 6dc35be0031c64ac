// AD-XML: every golden diagram and example goes .ad -> AD-XML -> .ad unchanged up to the
// normalisation of formatText, and its XML form gives the same tables and the same bytecode;
// mistakes in the XML are A0xx diagnostics at the element's or attribute's line:col.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "ad_fixture.hpp"
#include "bytecode/disassembler.hpp"
#include "lang/ad/decompose.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/tables.hpp"
#include "lang/ad/writer.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;
using virtcom::test::readFile;

namespace virtcom::ad {
namespace {

std::vector<fs::path> diagramFiles() {
  std::vector<fs::path> files;
  for (const char* dir : {"tests/golden/ad", "examples/activity"})
    for (const auto& entry : fs::directory_iterator(fs::path(VIRTCOM_SOURCE_DIR) / dir))
      if (entry.path().extension() == ".ad") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

Program readClean(const std::string& text, bool xml) {
  Diagnostics diags;
  Program program = xml ? readXmlProgram(0, text, diags) : readProgram(0, text, diags);
  EXPECT_FALSE(diags.hasErrors()) << test::codesAndPlaces(diags) << (diags.all().empty() ? "" : diags.all()[0].message);
  return program;
}

std::string tablesOf(const Program& program) {
  std::vector<DiagramTables> tables;
  for (const Diagram& d : program.diagrams) tables.push_back(decompose(d));
  return formatTables(program, tables, TableFormat::Text);
}

// The instructions of every POU, without the `; file:line:col` of each (the two forms place
// their elements on different lines).
std::string disassembly(const std::string& path, const std::string& text) {
  Diagnostics diags;
  auto module = test::compileText(path, text, diags);
  if (!module) return "<does not compile: " + test::codesAndPlaces(diags) + ">";
  std::string out;
  for (uint32_t pou = 0; pou < module->pous.size(); ++pou) {
    std::istringstream lines(bc::disassemble(*module, pou));
    for (std::string line; std::getline(lines, line);) out += line.substr(0, line.find(" ; ")) + "\n";
  }
  return out;
}

class XmlRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(XmlRoundTrip, TextToXmlToTextIsTheNormalisedText) {
  Program original = readClean(readFile(GetParam()), false);
  std::string xml = formatXml(original);
  Program fromXml = readClean(xml, true);
  EXPECT_EQ(formatText(fromXml), formatText(original));
  EXPECT_EQ(formatXml(fromXml), xml) << "the XML is a fixed point";
  EXPECT_EQ(formatText(readClean(formatText(original), false)), formatText(original)) << "so is the text";
}

TEST_P(XmlRoundTrip, XmlGivesTheSameTablesAndBytecode) {
  std::string text = readFile(GetParam());
  Program original = readClean(text, false);
  std::string xml = formatXml(original);
  EXPECT_EQ(tablesOf(readClean(xml, true)), tablesOf(original));
  std::string bytecode = disassembly("d.ad", text);
  EXPECT_EQ(disassembly("d.adxml", xml), bytecode);
  EXPECT_EQ(bytecode.find("does not compile"), std::string::npos) << bytecode;
}

INSTANTIATE_TEST_SUITE_P(Ad, XmlRoundTrip, ::testing::ValuesIn(diagramFiles()),
                         [](const auto& info) { return info.param.stem().string(); });

TEST(XmlNormalisation, CommentsLayoutCaseAndDefaultVariablesAreNormalised) {
  Program p = readClean("// a comment\nPROGRAM x\nPort  a i\nDIAGRAM d\n start s\n  a -> b\n activity a a\n"
                        " activity b B_out // bound\n timer t ton t#1500ms\n b -> t\nend_diagram\n",
                        false);
  EXPECT_EQ(formatText(p),
            "program x\nport a I\n\ndiagram d\n  start s\n  activity a\n  activity b B_out\n  timer t TON T#1s500ms\n\n"
            "  a -> b\n  b -> t\nend_diagram\n");
}

std::string diagnose(const std::string& xml) {
  Diagnostics diags;
  readXmlProgram(0, xml, diags);
  std::string out = test::codesAndPlaces(diags);
  for (const Diagnostic& d : diags.all()) out += d.message + "\n";
  return out;
}

constexpr const char* kHead = "<program name=\"P\">\n  <port name=\"A\" kind=\"I\"/>\n  <diagram name=\"D\">\n";

TEST(XmlErrors, UnknownElementIsA002AtItsTag) {
  EXPECT_EQ(diagnose(std::string(kHead) + "    <start id=\"S\"/>\n    <gate id=\"G\"/>\n  </diagram>\n</program>\n"),
            "A002 5:5\nunknown element <gate> (expected an element (<activity>, <timer>, <or-join>, ...) or an <arc>)\n");
}

TEST(XmlErrors, MissingAndUnknownAttributesAreA001) {
  EXPECT_EQ(diagnose(std::string(kHead) + "    <start id=\"S\"/>\n    <timer id=\"T\" type=\"TON\"/>\n"
                                          "    <activity id=\"A\" colour=\"red\"/>\n  </diagram>\n</program>\n"),
            "A001 5:5\nA001 6:30\n<timer> needs the attribute 'preset'\n"
            "<activity> has no attribute 'colour' (expected id, variable)\n");
}

TEST(XmlErrors, DanglingArcIsA004AtTheAttributeValue) {
  EXPECT_EQ(diagnose(std::string(kHead) + "    <start id=\"S\"/>\n    <activity id=\"A\"/>\n"
                                          "    <arc from=\"S\" to=\"A\"/>\n    <arc from=\"A\" to=\"Nowhere\"/>\n"
                                          "  </diagram>\n</program>\n"),
            "A004 7:23\nthe arc names 'Nowhere', which diagram 'D' does not declare\n");
}

TEST(XmlErrors, ValuesAreCheckedAsInTheTextForm) {
  EXPECT_EQ(diagnose(std::string(kHead) + "    <start id=\"S\"/>\n    <timer id=\"T\" type=\"TON\" preset=\"5s\"/>\n"
                                          "    <arc from=\"S\" to=\"T\" kind=\"sideways\"/>\n  </diagram>\n</program>\n"),
            "A012 5:38\nA001 6:32\ntimer preset '5s' is not a duration such as T#5s\n"
            "arc kind 'sideways' is not normal, NOT-IN or NOT-OUT\n");
}

TEST(XmlErrors, MalformedXmlAndWrongRootAreA014) {
  EXPECT_EQ(diagnose("<program name=\"P\">\n  <diagram name=\"D\">\n</program>\n"),
            "A014 3:3\nmalformed XML: Start-end tags mismatch\n");
  EXPECT_EQ(diagnose("<?xml version=\"1.0\"?>\n<project/>\n"),
            "A014 2:1\nthe root element is <project>; an AD-XML file is one <program name=\"...\">\n");
}

TEST(XmlErrors, StructuralChecksRunOnTheXmlForm) {
  // No start activity: A008 at the diagram, as for the text form.
  EXPECT_EQ(diagnose(std::string(kHead) + "    <activity id=\"A\"/>\n    <activity id=\"B\" variable=\"Y\"/>\n"
                                          "    <arc from=\"A\" to=\"B\"/>\n  </diagram>\n</program>\n")
                .substr(0, 9),
            "A008 3:3\n");
}

}  // namespace
}  // namespace virtcom::ad
