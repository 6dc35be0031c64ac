// Cell-file mistakes in device entries, reported with file:line:col as the user sees them.
#include <gtest/gtest.h>

#include "plant/device_errors.hpp"
#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const char* kMinimalRobot = R"(max_speed: 500 mm/s
acceleration: 1 m/s^2
locations:
  Home: "0, 0, 0 mm"
  Pick: { at: "100, 0, 0 mm", zone: Z1 }
procedures:
  1: { name: P1, steps: [move Pick] }
)";

TEST(DeviceConfig, UnknownDeviceTypeListsTheKnownOnes) {
  PlantRig rig;
  EXPECT_EQ(rig.add("robto", "R", "type: robto\n"), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(),
                       "R.yaml:1:7: error[C010]: unknown device type 'robto' (expected one of: robot, axis, press, "
                       "timed, conveyor, sensor, tank, valve, pump, heater, level_switch, temperature_sensor)"))
      << rig.renderedDiags();
}

TEST(DeviceConfig, EveryTypeIsListedWithADescription) {
  auto types = deviceTypes();
  ASSERT_EQ(types.size(), 12u);
  for (const auto& [name, doc] : types) EXPECT_FALSE(doc.empty()) << name;
}

// The loader checks the wiring of an entry with parameter mistakes in the same run, so every
// factory yields its device, with its ports, even then (and its constructor copes with the
// wrong values, e.g. a negative conveyor length).
TEST(DeviceConfig, AnEntryWithMistakesStillYieldsItsDeviceWithItsPorts) {
  struct Case {
    const char* type;
    const char* yaml;
    const char* port;
  };
  for (const Case& k : {Case{"robot", "max_speed: -1 mm/s\n", "procedureNumber"},
                        Case{"axis", "max_speed: 0 mm/s\n", "targetPosition"},
                        Case{"press", "stroke: 5 W\n", "actualForce"}, Case{"timed", "busy_power: 5 mm\n", "done"},
                        Case{"conveyor", "speed: 1 m/s\nlength: -1 m\n", "moving"},
                        Case{"sensor", "delay: -1 s\n", "value"}}) {
    SCOPED_TRACE(k.type);
    SourceManager sources;
    Diagnostics diags;
    Trace trace;
    World world(trace);
    const ConfigNode node = MiniYaml::parse(k.yaml, sources.addFile("d.yaml", k.yaml));
    ConfigReader reader(node, diags, "device");
    std::unique_ptr<Device> d = createDevice(k.type, "D", reader, world);
    EXPECT_TRUE(diags.hasErrors());
    ASSERT_NE(d, nullptr);
    EXPECT_GE(d->portIndex(k.port), 0);
  }
}

TEST(DeviceConfig, MinimalRobotLoads) {
  PlantRig rig;
  Device* d = rig.add("robot", "R", kMinimalRobot);
  ASSERT_NE(d, nullptr) << rig.renderedDiags();
  EXPECT_EQ(d->type(), "robot");
  std::vector<std::string> ports;
  for (const auto& p : d->ports()) ports.push_back(p.name);
  EXPECT_EQ(ports, (std::vector<std::string>{"procedureNumber", "execute", "done", "error", "busy", "actualX", "actualY",
                                             "actualZ", "toolAttached"}));
  EXPECT_EQ(d->ports()[0].type, ElemType::Int);
  EXPECT_EQ(d->ports()[0].dir, PortDir::In);
  EXPECT_EQ(d->ports()[2].dir, PortDir::Out);
}

TEST(DeviceConfig, TypoInAKeyIsAnUnknownKeyAtItsLine) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "max_sped: 2 m/s\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(), "R.yaml:8:1: error[C011]: unknown key 'max_sped' in device 'R'"))
      << rig.renderedDiags();
}

TEST(DeviceConfig, TypeNameAndGroupAreAccepted) {
  PlantRig rig;
  std::string yaml = std::string("type: robot\ngroup: Robots\n") + kMinimalRobot;
  Device* d = rig.add("robot", "R", yaml);
  ASSERT_NE(d, nullptr) << rig.renderedDiags();
  rig.prepare();
  EXPECT_EQ(rig.trace.devices[d->traceIndex()].group, "Robots");
}

TEST(DeviceConfig, MissingUnitIsReportedAtTheValue) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml.replace(yaml.find("500 mm/s"), 8, "500");
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(), "R.yaml:1:12: error[C010]: 'max_speed': '500' needs a unit: expected a speed"))
      << rig.renderedDiags();
}

TEST(DeviceConfig, WrongDimensionIsReported) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml.replace(yaml.find("1 m/s^2"), 7, "1 m/s");
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(), "R.yaml:2:15: error[C010]: 'acceleration': '1 m/s' is not an acceleration"))
      << rig.renderedDiags();
}

TEST(DeviceConfig, UnknownLocationInAStepPointsAtTheStep) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "  2: { name: P2, steps: [move Home, move Pikc] }\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(),
                       "R.yaml:8:37: error[C010]: unknown location 'Pikc' (expected one of: Home, Pick)"))
      << rig.renderedDiags();
}

TEST(DeviceConfig, UnknownStepKeywordAndMissingArgument) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "  2:\n    name: P2\n    steps:\n      - mvoe Home\n      - attach\n      - detach now\n      - wait 3\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:11:9: error[C010]: unknown step 'mvoe' (expected one of: move, attach, detach, grip, "
                            "release, screw, wait, require, set, clear)"))
      << out;
  EXPECT_TRUE(contains(out, "R.yaml:12:9: error[C010]: 'attach' needs a tool")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:13:9: error[C010]: 'detach' takes no argument, found 'now'")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:14:9: error[C010]: 'wait': '3' needs a unit")) << out;
}

TEST(DeviceConfig, UnknownToolAndToolKindAndMagazine) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "  2: { name: P2, steps: [attach Grippr] }\n"
          "tool_change_time: 1 s\n"
          "tools:\n"
          "  Gripper: { kind: pincer, magazine: Shelf }\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:8:26: error[C010]: unknown tool 'Grippr' (expected one of: Gripper)")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:11:20: error[C010]: unknown tool kind 'pincer' (expected one of: parallel_gripper, "
                            "centric_gripper, screwer, insert_handler, generic)"))
      << out;
  EXPECT_TRUE(contains(out, "R.yaml:11:38: error[C010]: unknown magazine location 'Shelf'")) << out;
}

TEST(DeviceConfig, ScrewerNeedsRundownTimeAndToolsNeedAChangeTime) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "tools:\n  S: { kind: screwer }\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:9:6: error[C010]: tool 'S' needs 'rundown_time'")) << out;
  EXPECT_TRUE(contains(out, "has tools but no 'tool_change_time'")) << out;
}

TEST(DeviceConfig, UnknownKeyInsideAToolOrLocation) {
  PlantRig rig;
  std::string y2 = R"(max_speed: 500 mm/s
acceleration: 1 m/s^2
locations:
  Home: { at: "0, 0, 0 mm", zoen: Z }
procedures:
  1: { name: P1, steps: [], sped: 3 }
)";
  EXPECT_EQ(rig.add("robot", "R", y2), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:4:29: error[C011]: unknown key 'zoen' in location 'Home'")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:6:29: error[C011]: unknown key 'sped' in procedure 1 of robot 'R'")) << out;
}

TEST(DeviceConfig, LocationNeedsThreeCoordinates) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml.replace(yaml.find("\"0, 0, 0 mm\""), 12, "\"0, 0 mm\"");
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  EXPECT_TRUE(contains(rig.renderedDiags(), "R.yaml:4:9: error[C010]: 'Home' needs 3 values, found 2")) << rig.renderedDiags();
}

TEST(DeviceConfig, BadProcedureNumbers) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "  one: { name: P, steps: [] }\n  1: { name: Again, steps: [] }\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:8:3: error[C010]: command number 'one' must be a whole number from 1 to 32767")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:9:6: error[C010]: procedure number 1 is defined twice")) << out;
}

TEST(DeviceConfig, UnknownHomeAndBadPartMass) {
  PlantRig rig;
  std::string yaml = kMinimalRobot;
  yaml += "home: Hmoe\nparts:\n  bearing: heavy\n";
  EXPECT_EQ(rig.add("robot", "R", yaml), nullptr);
  const std::string out = rig.renderedDiags();
  EXPECT_TRUE(contains(out, "R.yaml:8:7: error[C010]: unknown home location 'Hmoe'")) << out;
  EXPECT_TRUE(contains(out, "R.yaml:10:12: error[C010]: 'bearing': expected a mass")) << out;
}

TEST(DeviceConfig, AllProblemsOfAnEntryAreReportedInOnePass) {
  PlantRig rig;
  EXPECT_EQ(rig.add("robot", "R", "max_speed: fast\nfoo: 1\n"), nullptr);
  EXPECT_GE(rig.diags.errorCount(), 5u) << rig.renderedDiags();  // speed, acceleration, locations, procedures, foo
}

}  // namespace
}  // namespace virtcom::plant::test

namespace virtcom::plant::test {
namespace {

TEST(DeviceErrors, OneTableGivesCodesAndMeanings) {
  EXPECT_EQ(code(DeviceError::UnknownCommand), 10);
  EXPECT_EQ(code(DeviceError::NoInsert), 40);
  EXPECT_EQ(code(DeviceError::InjectedFault), 90);
  EXPECT_NE(std::string(deviceErrorMeaning(40)).find("insert"), std::string::npos);
  EXPECT_NE(std::string(deviceErrorMeaning(50)).find("stud"), std::string::npos);
  EXPECT_EQ(std::string(deviceErrorMeaning(77)), "unknown error code");
}

}  // namespace
}  // namespace virtcom::plant::test
