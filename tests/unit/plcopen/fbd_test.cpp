// FBD bodies, data types and CODESYS-style projects, run on the VM.
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

TEST(Fbd, FunctionsNegationsTypesAndInitialValues) {
  auto c = compileGolden("beremiz_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  plc.scan();
  EXPECT_EQ(plc.get("prg.scaled"), "63") << "user function Scale(21, 3)";
  EXPECT_EQ(plc.get("prg.big"), "FALSE") << "NOT (NOT (63 > 100)) through a negated output and a negated outVariable";
  EXPECT_EQ(plc.get("prg.sum"), "72") << "p.x=1 (type default), p.y=7, buf[2]=5 (3(5)), buf[3]=9, level=50";
  EXPECT_EQ(plc.get("prg.mode"), "Mode#Run");
  EXPECT_EQ(plc.get("prg.name"), "'cell & co'");
  plc.set("prg.raw", "40");
  plc.scan();
  EXPECT_EQ(plc.get("prg.big"), "TRUE");
}

TEST(Fbd, FeedbackThroughAnInstanceReadsThePreviousScan) {
  auto c = compileGolden("beremiz_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  // trig.CLK := NOT trig.Q (previous scan): Q is TRUE, FALSE, TRUE, ...; the connector carries Q
  // to the EN of ADD, so toggles counts the TRUE scans.
  const char* expectedQ[] = {"TRUE", "FALSE", "TRUE", "FALSE", "TRUE"};
  const char* expectedToggles[] = {"1", "1", "2", "2", "3"};
  for (int k = 0; k < 5; ++k) {
    plc.scan();
    EXPECT_EQ(plc.get("prg.osc.q"), expectedQ[k]) << "scan " << k;
    EXPECT_EQ(plc.get("prg.osc.toggles"), expectedToggles[k]) << "scan " << k;
  }
}

TEST(Codesys, StBodiesMethodsGlobalVarsAndEntities) {
  auto c = compileGolden("codesys_st.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  EXPECT_EQ(c->diags.warningCount(), 0u) << c->rendered();
  Plc plc(*c->module);
  plc.scan(3);
  EXPECT_EQ(plc.get("PLC_PRG.resets"), "1") << "count reached limit 3 and Reset() ran";
  EXPECT_EQ(plc.get("PLC_PRG.counter.count"), "0");
  plc.scan(3);
  EXPECT_EQ(plc.get("PLC_PRG.resets"), "2");
  EXPECT_EQ(plc.get("GVL.gScans"), "6");
  EXPECT_EQ(plc.get("PLC_PRG.axis.pos"), "3.0");
}

TEST(Mixed, XmlAndStFilesCompileTogether) {
  std::string st = "PROGRAM Extra\nVAR n : INT; END_VAR\nn := Scale(raw := 5, factor := 4);\nEND_PROGRAM\n";
  auto c = compile({input("beremiz_fbd.xml", readFile(kGoldenDir / "beremiz_fbd.xml")), input("extra.st", st)});
  ASSERT_NE(c->module, nullptr) << c->rendered();
}

}  // namespace
}  // namespace virtcom::plcopen::testing
