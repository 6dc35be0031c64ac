// PLCopen XML as CODESYS and older tools write it: application objects in the resource's vendor
// data, ISO 8601 task intervals, typeName="", EXTENDS/IMPLEMENTS and INTERFACE as vendor data,
// named global lists in a resource, TC6 1.0 files.
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

const bc::TaskInfo* taskNamed(const bc::Module& m, const std::string& name) {
  for (const bc::TaskInfo& t : m.tasks)
    if (t.name == name) return &t;
  return nullptr;
}

TEST(CodesysExport, ApplicationObjectsInheritanceInterfacesAndNamedGlobalsRun) {
  auto c = compileGolden("codesys_application.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  EXPECT_EQ(c->diags.warningCount(), 0u) << c->rendered();
  Plc plc(*c->module);
  plc.scan(3);
  EXPECT_EQ(plc.get("PLC_PRG.lift.pos"), "3") << "FB_Lift EXTENDS FB_Axis: SUPER^() ran the base body";
  EXPECT_EQ(plc.get("PLC_PRG.last"), "30") << "Step called through the I_Stepper interface";
  EXPECT_EQ(plc.get("PLC_PRG.pose.x"), "3.0") << "ST_Pose EXTENDS ST_Pos has the base's field";
  EXPECT_EQ(plc.get("PLC_PRG.pose.angle"), "90.0");
  EXPECT_EQ(plc.get("GVL_IO.nTicks"), "3") << "a named <globalVars> of the resource is qualified by its name";
  EXPECT_EQ(plc.get("GVL_IO.xUp"), "TRUE");
}

TEST(CodesysExport, IsoDurationIntervalAndEmptyTypeNameMakeTheTask) {
  auto c = compileGolden("codesys_application.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  const bc::TaskInfo* task = taskNamed(*c->module, "MainTask");
  ASSERT_NE(task, nullptr);
  EXPECT_EQ(task->intervalNs, 20'000'000) << "PT0.02S";
  EXPECT_EQ(task->programs.size(), 1u) << "pouInstance PLC_PRG with typeName=\"\" runs PLC_PRG";
}

TEST(CodesysExport, IntervalNotationsAllGiveTheSameTask) {
  for (const char* interval : {"T#250ms", "PT0.25S", "P0DT0H0M0.25S", "00:00:00.250", "PT0.0041666666666666667M"}) {
    std::string xml = std::string(R"(<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><dataTypes/><pous>)"
                                  R"(<pou name="P" pouType="program"><body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">;</xhtml></ST></body></pou>)"
                                  R"(</pous></types><instances><configurations><configuration name="C"><resource name="R">)"
                                  R"(<task name="T" priority="1" interval=")") +
                      interval + R"("><pouInstance name="p" typeName="P"/></task></resource></configuration></configurations></instances></project>)";
    auto c = compile({input("interval.xml", xml)});
    ASSERT_NE(c->module, nullptr) << interval << "\n" << c->rendered();
    const bc::TaskInfo* task = taskNamed(*c->module, "T");
    ASSERT_NE(task, nullptr);
    EXPECT_NEAR(static_cast<double>(task->intervalNs), 250e6, 1e3) << interval;
  }
}

TEST(CodesysExport, AYearOrMonthIsNoInterval) {
  std::string xml = R"(<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><dataTypes/><pous>)"
                    R"(<pou name="P" pouType="program"><body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">;</xhtml></ST></body></pou>)"
                    R"(</pous></types><instances><configurations><configuration name="C"><resource name="R">)"
                    R"(<task name="T" priority="1" interval="P1M"><pouInstance name="p" typeName="P"/></task></resource></configuration></configurations></instances></project>)";
  auto c = compile({input("interval.xml", xml)});
  EXPECT_EQ(c->module, nullptr);
  EXPECT_NE(c->rendered().find("interval.xml:1:"), std::string::npos) << c->rendered();
}

TEST(Tc6Version1, ProjectWithTypeAttributeAndXsdTimeIntervalRuns) {
  auto c = compileGolden("tc6_v10.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  const bc::TaskInfo* task = taskNamed(*c->module, "Slow");
  ASSERT_NE(task, nullptr);
  EXPECT_EQ(task->intervalNs, 50'000'000);
  Plc plc(*c->module);
  plc.scan(3);
  EXPECT_EQ(plc.get("blink.scans"), "3");
  EXPECT_EQ(plc.get("blink.lamp"), "TRUE");
}

}  // namespace
}  // namespace virtcom::plcopen::testing
