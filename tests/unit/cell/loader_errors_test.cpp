// Every class of cell-file mistake is reported at its exact `file:line:col` with its code and
// message (docs/cell-file.md: "Every mistake is reported with file:line:col"), and all
// mistakes of one file come out of one load.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cell_files.hpp"

namespace virtcom::cell::test {
namespace {

using ::testing::ElementsAre;

class LoaderErrors : public CellFiles {
 protected:
  void SetUp() override {
    CellFiles::SetUp();
    write("main.st", kMainSt);
  }
  // Loads cell.yaml = `text`; the load must fail, with errors only.
  std::vector<std::string> fails(const std::string& text) {
    std::vector<std::string> found = CellFiles::fails(text);
    EXPECT_EQ(diags_.errorCount(), diags_.all().size());
    return found;
  }
};

TEST_F(LoaderErrors, MissingCellFileIsReportedWithoutLocation) {
  auto cell = load("nowhere.yaml");
  EXPECT_EQ(cell, nullptr);
  EXPECT_THAT(errors(), ElementsAre("error[C002]: cannot read cell file 'nowhere.yaml'"));
}

TEST_F(LoaderErrors, YamlSyntaxErrorAtItsPosition) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "  cycle_time: 10 ms: 5\n"
                    "devices: []\n"),
              ElementsAre("cell.yaml:4:20: error[C001]: YAML syntax error: mapping values are not allowed in this context"));
  // rendered like a compiler error: the line quoted, a caret under the column
  EXPECT_EQ(rendered(),
            "cell.yaml:4:20: error[C001]: YAML syntax error: mapping values are not allowed in this context\n"
            "    cycle_time: 10 ms: 5\n"
            "                     ^\n"
            "1 error(s), 0 warning(s)\n");
}

// Found by fuzz_ads_routes (2026-12-05): 3,087 `{` in a row overflowed the stack of the tree
// builder. Nesting beyond 256 sequences and mappings is now a syntax error at the first one too
// deep, for every YAML file the loader reads (cell, mapping, routes, scenario files).
TEST_F(LoaderErrors, NestingTooDeepIsAnErrorNotACrash) {
  EXPECT_THAT(fails("name: x\nplc: " + std::string(3087, '{') + "\n"),
              ElementsAre("cell.yaml:2:261: error[C001]: YAML syntax error: sequences and mappings nested more than 256 deep"));
  EXPECT_THAT(fails("name: x\nplc: " + std::string(100000, '[') + "\n"),
              ElementsAre("cell.yaml:2:261: error[C001]: YAML syntax error: sequences and mappings nested more than 256 deep"));
}

// A key written twice in one mapping is an error at the second, naming the first (issue 16: the
// first used to win silently); every duplicate of the file is reported, at any depth.
TEST_F(LoaderErrors, DuplicateKeysAreErrorsNamingTheFirst) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "  cycle_time: 10 ms\n"
                    "  cycle_time: 20 ms\n"
                    "devices:\n"
                    "  - name: Press\n"
                    "    type: press\n"
                    "    press_time: 1 s\n"
                    "    press_time: 2 s\n"
                    "name: y\n"),
              ElementsAre("cell.yaml:5:3: error[C003]: duplicate key 'cycle_time' (first at line 4, column 3; a key "
                          "may appear once per mapping)",
                          "cell.yaml:10:5: error[C003]: duplicate key 'press_time' (first at line 9, column 5; a key "
                          "may appear once per mapping)",
                          "cell.yaml:11:1: error[C003]: duplicate key 'name' (first at line 1, column 1; a key may "
                          "appear once per mapping)"));
}

// The same key in two different mappings is no duplicate.
TEST_F(LoaderErrors, SameKeyInTwoMappingsIsNoDuplicate) {
  loads("name: x\n"
        "plc:\n"
        "  sources: [main.st]\n"
        "  cycle_time: 10 ms\n"
        "devices:\n"
        "  - name: Clamp\n"
        "    type: timed\n"
        "    commands:\n"
        "      1: { name: Close, duration: 1 s }\n"
        "      2: { name: Open, duration: 1 s }\n");
}

// A PLC program that does not compile is the one cause to read: its errors come first (before an
// unrelated mistake of the cell file, which is still reported) and the wired devices do not each
// add a consequential "the cell has no soft PLC" (issue 16).
TEST_F(LoaderErrors, CompileErrorsComeFirstWithoutConsequentialWiringErrors) {
  write("broken.st", "PROGRAM MAIN\nVAR\n  count : INT;\nEND_VAR\ncount := nothing + 1;\nEND_PROGRAM\n");
  std::vector<std::string> found = fails("name: x\n"
                                         "plc:\n"
                                         "  sources: [broken.st]\n"
                                         "devices:\n"
                                         "  - name: Clamp\n"
                                         "    type: timed\n"
                                         "    comands: {}\n" +
                                         std::string(kClampParams) +
                                         "    wiring: MAIN.Clamp\n"
                                         "  - name: Lock\n"
                                         "    type: timed\n" +
                                         std::string(kClampParams) +
                                         "    wiring: { execute: MAIN.exec }\n");
  ASSERT_EQ(found.size(), 2u) << rendered();
  EXPECT_THAT(found[0], ::testing::StartsWith("broken.st:5:10: error[E"));
  EXPECT_THAT(found[0], ::testing::HasSubstr("'nothing'"));
  EXPECT_THAT(found[1], ::testing::StartsWith("cell.yaml:7:5: error[C011]: unknown key 'comands'"));
}

TEST_F(LoaderErrors, UnknownTopLevelKeyListsTheKnownOnes) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "devices: []\n"
                    "devcies: []\n"),
              ElementsAre("cell.yaml:5:1: error[C011]: unknown key 'devcies' in the cell file "
                          "(expected one of: name, plc, run, zones, world, devices, modbus, hmi, plan, extends, replace_devices)"));
}

// A valve, pump, heater or tank sensor naming a tank no entry defines, at the name.
TEST_F(LoaderErrors, DeviceNamesATankNoEntryDefines) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "devices:\n"
                    "  - name: Reactor\n"
                    "    type: tank\n"
                    "    capacity: 100 l\n"
                    "  - name: Fill\n"
                    "    type: valve\n"
                    "    to: Reactr\n"
                    "    flow: 1 l/s\n"),
              ElementsAre("cell.yaml:10:9: error[C010]: no tank named 'Reactr' (expected the name of a device of type "
                          "tank; the cell has Reactor)"));
}

TEST_F(LoaderErrors, ExtendsNamesAMissingFile) {
  EXPECT_THAT(fails("extends: nowhere.yaml\ndevices: []\n"),
              ElementsAre("cell.yaml:1:10: error[C002]: cannot read cell file 'nowhere.yaml' named by 'extends'"));
}

TEST_F(LoaderErrors, ExtendsDoesNotChain) {
  write("base.yaml", "extends: cell.yaml\ndevices: []\n");
  EXPECT_THAT(fails("extends: base.yaml\n"),
              ElementsAre("base.yaml:1:1: error[C010]: a cell file named by 'extends' cannot itself extend another file"));
}

TEST_F(LoaderErrors, ReplaceDevicesNamesDevicesOfTheBase) {
  write("base.yaml", "plc:\n  sources: [main.st]\ndevices:\n  - name: Lock\n    type: timed\n"
                     "    commands: { 1: { name: Lock, duration: 1 s } }\n");
  EXPECT_THAT(fails("extends: base.yaml\n"
                    "replace_devices:\n"
                    "  - name: Lokc\n"
                    "  - type: timed\n"
                    "  - { name: Lock, type: timed, commands: { 1: { name: A, duration: 1 s } } }\n"
                    "  - { name: Lock, type: timed, commands: { 1: { name: B, duration: 1 s } } }\n"),
              ElementsAre("cell.yaml:3:11: error[C010]: 'replace_devices': the base file has no device 'Lokc' to replace",
                          "cell.yaml:4:5: error[C010]: 'replace_devices': every entry needs the 'name' of the base "
                          "file's device it replaces",
                          "cell.yaml:6:13: error[C010]: 'replace_devices': device 'Lock' is replaced twice"));
}

TEST_F(LoaderErrors, ReplaceDevicesNeedsExtendsAndTheBasesDevices) {
  EXPECT_THAT(fails("plc:\n  sources: [main.st]\ndevices: []\nreplace_devices: []\n"),
              ElementsAre("cell.yaml:4:1: error[C010]: 'replace_devices' replaces devices of the cell file named by "
                          "'extends', but this file has no 'extends'",
                          "cell.yaml:4:1: error[C010]: 'replace_devices' replaces devices of the base file, but this file "
                          "has its own 'devices'"));
}

TEST_F(LoaderErrors, PlcWithBothSourcesAndModbus) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "  modbus: { address: 127.0.0.1:1502 }\n"
                    "devices: []\n"),
              ElementsAre("cell.yaml:4:11: error[C010]: 'plc' has either 'sources' (the soft PLC) or 'modbus' (an external "
                          "PLC), not both"));
}

TEST_F(LoaderErrors, MissingDevicesSection) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"),
              ElementsAre("cell.yaml:1:1: error[C010]: the cell file needs 'devices:', a list of devices"));
}

TEST_F(LoaderErrors, UnreadableStSourceAtItsListItem) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st, missing.st]\n"
                    "devices: []\n"),
              ElementsAre("cell.yaml:3:22: error[C010]: cannot read PLC source 'missing.st'"));
}

TEST_F(LoaderErrors, StCompileErrorIsRenderedAtTheStFile) {
  write("broken.st",
        "PROGRAM MAIN\n"
        "VAR\n"
        "  x : INT;\n"
        "END_VAR\n"
        "x := y + 1;\n"
        "END_PROGRAM\n");
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [broken.st]\n"
                    "devices: []\n"),
              ElementsAre("broken.st:5:6: error[E201]: 'y' is not declared"));
  EXPECT_EQ(rendered(),
            "broken.st:5:6: error[E201]: 'y' is not declared\n"
            "  x := y + 1;\n"
            "       ^\n"
            "1 error(s), 0 warning(s)\n");
}

TEST_F(LoaderErrors, UnknownDeviceTypeAtTheTypeValue) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "devices:\n"
                    "  - name: Gizmo\n"
                    "    type: teleporter\n"),
              ElementsAre("cell.yaml:6:11: error[C010]: unknown device type 'teleporter' (expected one of: robot, "
                          "axis, press, timed, conveyor, sensor, tank, valve, pump, heater, level_switch, "
                          "temperature_sensor, g120, powerflex525, powerflex750, s120_epos)"));
}

TEST_F(LoaderErrors, DuplicateDeviceNameAtTheSecondEntry) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams +
                    "  - name: Clamp\n"
                    "    type: timed\n" +
                    kClampParams),
              ElementsAre("cell.yaml:9:5: error[C010]: a device named 'Clamp' already exists"));
}

TEST_F(LoaderErrors, UnknownDeviceParameterIsATypo) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n"
                                "    idle_powr: 5 W\n") +
                    kClampParams),
              ElementsAre("cell.yaml:7:5: error[C011]: unknown key 'idle_powr' in device (expected one of: name, type, "
                          "wiring, faults, model, description, command_port, idle_power, busy_power, commands, group)"));
}

TEST_F(LoaderErrors, QuantityWithoutUnit) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "devices:\n"
                    "  - name: Clamp\n"
                    "    type: timed\n"
                    "    commands:\n"
                    "      1: { name: Close, duration: 1 }\n"),
              ElementsAre("cell.yaml:8:35: error[C010]: 'duration': '1' needs a unit: expected a duration (e.g. 2 s, "
                          "150 ms)"));
}

TEST_F(LoaderErrors, QuantityOfTheWrongDimension) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n"
                                "    busy_power: 5 mm\n") +
                    kClampParams),
              ElementsAre("cell.yaml:7:17: error[C010]: 'busy_power': '5 mm' is not a power (e.g. 150 W)"));
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "  cycle_time: 10 mm\n"
                    "devices: []\n"),
              ElementsAre("cell.yaml:4:15: error[C010]: 'cycle_time': '10 mm' is not a duration (e.g. 2 s, 150 ms)"));
}

TEST_F(LoaderErrors, WiringToAMissingPlcVariable) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams +
                    "    wiring:\n"
                    "      execute: MAIN.exec\n"
                    "      done: MAIN.dnoe\n"),
              ElementsAre("cell.yaml:11:13: error[C032]: the PLC has no variable 'MAIN.dnoe' to wire to Clamp.done"));
}

TEST_F(LoaderErrors, WiringToAPortTheDeviceDoesNotHave) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams +
                    "    wiring:\n"
                    "      exec: MAIN.exec\n"),
              ElementsAre("cell.yaml:10:7: error[C031]: device 'Clamp' has no port 'exec' (ports: programNumber, "
                          "execute, done, error, busy)"));
}

TEST_F(LoaderErrors, WiringTypeMismatchBothDirections) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams +
                    "    wiring:\n"
                    "      done: MAIN.count\n"
                    "      execute: MAIN.cmd\n"
                    "      programNumber: MAIN.exec\n"),
              ElementsAre("cell.yaml:10:13: error[C033]: 'MAIN.count' is INT but output 'done' of Clamp is BOOL",
                          "cell.yaml:11:16: error[C033]: 'MAIN.cmd' is INT but input 'execute' of Clamp is BOOL",
                          "cell.yaml:12:22: error[C033]: 'MAIN.exec' is BOOL but input 'programNumber' of Clamp is INT"));
}

TEST_F(LoaderErrors, OutputPortToAConstant) {
  // reading a CONSTANT into an input port is fine; writing an output into one is not
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams +
                    "    wiring:\n"
                    "      execute: MAIN.kLocked\n"
                    "      done: MAIN.kLocked\n"),
              ElementsAre("cell.yaml:11:13: error[C033]: 'MAIN.kLocked' is read-only (CONSTANT) and cannot receive "
                          "Clamp.done"));
}

TEST_F(LoaderErrors, PrefixWiringThatMatchesNothing) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams + "    wiring: MAIN.Clmap\n"),
              ElementsAre("cell.yaml:9:13: error[C030]: no port of 'Clamp' matches a variable under 'MAIN.Clmap' "
                          "(expected e.g. MAIN.Clmap.programNumber)"));
}

TEST_F(LoaderErrors, BadUntilConditions) {
  const std::string head = "name: x\nplc:\n  sources: [main.st]\nrun:\n  until: ";
  const std::string tail = "\ndevices: []\n";
  EXPECT_THAT(fails(head + "\"MAIN.nothing >= 3\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.nothing >= 3': the PLC has no variable "
                          "'MAIN.nothing'"));
  EXPECT_THAT(fails(head + "\"MAIN.count >= banana\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.count >= banana': invalid INT literal 'banana'"));
  EXPECT_THAT(fails(head + "\"MAIN.Clamp = 1\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.Clamp = 1': 'MAIN.Clamp' is not an elementary "
                          "variable"));
}

// A mistyped operator is named as the operator, with the valid ones (issue 16: `> =` used to be
// read as part of the variable's name, "no variable 'MAIN.count >'").
TEST_F(LoaderErrors, BadUntilOperatorListsTheValidOnes) {
  const std::string head = "name: x\nplc:\n  sources: [main.st]\nrun:\n  until: ";
  const std::string tail = "\ndevices: []\n";
  const std::string expected = "' is not a comparison operator (expected one of: =, <>, <, <=, >, >=; == and != are accepted too)";
  EXPECT_THAT(fails(head + "\"MAIN.count > = 3\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.count > = 3': '> =" + expected));
  EXPECT_THAT(fails(head + "\"MAIN.count => 3\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.count => 3': '=>" + expected));
  EXPECT_THAT(fails(head + "\"MAIN.count gt 3\"" + tail),
              ElementsAre("cell.yaml:5:10: error[C020]: condition 'MAIN.count gt 3': 'gt" + expected));
  // the valid forms, with and without spaces, and a BOOL alone
  for (const char* ok : {"MAIN.count>=3", "MAIN.count <> 3", "MAIN.count == 3", "MAIN.count != 3", "MAIN.finished"})
    loads(head + "\"" + ok + "\"" + tail);
}

TEST_F(LoaderErrors, CycleDoneMustBeBool) {
  const std::string head = "name: x\nplc:\n  sources: [main.st]\nrun:\n  cycle_done: ";
  const std::string tail = "\ndevices: []\n";
  EXPECT_THAT(fails(head + "MAIN.count" + tail),
              ElementsAre("cell.yaml:5:15: error[C010]: 'cycle_done' must name a BOOL PLC variable; 'MAIN.count' is not "
                          "one"));
  EXPECT_THAT(fails(head + "MAIN.nothing" + tail),
              ElementsAre("cell.yaml:5:15: error[C010]: 'cycle_done' must name a BOOL PLC variable; 'MAIN.nothing' is not "
                          "one"));
}

TEST_F(LoaderErrors, AllMistakesOfOneFileInOnePass) {
  EXPECT_THAT(fails(std::string("name: x\n"                              // 1
                                "plc:\n"                                 // 2
                                "  sources: [main.st]\n"                 // 3
                                "run:\n"                                 // 4
                                "  cycle_done: MAIN.cmd\n"               // 5
                                "  until: \"MAIN.nothing >= 3\"\n"       // 6
                                "  tme_limit: 5 s\n"                     // 7
                                "devices:\n"                             // 8
                                "  - name: Clamp\n"                      // 9
                                "    type: timed\n") +                   // 10
                    kClampParams +                                       // 11, 12
                    "    wiring:\n"                                      // 13
                    "      done: MAIN.count\n"                           // 14
                    "      error: MAIN.missing\n"                        // 15
                    "  - name: Clamp\n"                                  // 16
                    "    type: timed\n" +                                // 17
                    kClampParams +                                       // 18, 19
                    "  - name: Gizmo\n"                                  // 20
                    "    type: teleporter\n"                             // 21
                    "  - name: Lock\n"                                   // 22
                    "    type: timed\n"                                  // 23
                    "    idle_powr: 5 W\n"                               // 24
                    "    commands:\n"                                    // 25
                    "      1: { name: Close, duration: 1 }\n"            // 26
                    "  - name: Lock3\n"                                  // 27
                    "    type: timed\n" +                                // 28
                    kClampParams +                                       // 29, 30
                    "    wiring: MAIN.nothing\n"                         // 31
                    "extra: 1\n"),                                       // 32
              ElementsAre("cell.yaml:5:15: error[C010]: 'cycle_done' must name a BOOL PLC variable; 'MAIN.cmd' is not one",
                          "cell.yaml:6:10: error[C020]: condition 'MAIN.nothing >= 3': the PLC has no variable "
                          "'MAIN.nothing'",
                          "cell.yaml:7:3: error[C011]: unknown key 'tme_limit' in 'run' (expected one of: time_limit, "
                          "until, cycle_done, cycles, stop_on_collision, stop_on_device_error, record)",
                          "cell.yaml:14:13: error[C033]: 'MAIN.count' is INT but output 'done' of Clamp is BOOL",
                          "cell.yaml:15:14: error[C032]: the PLC has no variable 'MAIN.missing' to wire to Clamp.error",
                          "cell.yaml:16:5: error[C010]: a device named 'Clamp' already exists",
                          "cell.yaml:21:11: error[C010]: unknown device type 'teleporter' (expected one of: robot, axis, "
                          "press, timed, conveyor, sensor, tank, valve, pump, heater, level_switch, temperature_sensor, g120, "
                          "powerflex525, powerflex750, s120_epos)",
                          "cell.yaml:24:5: error[C011]: unknown key 'idle_powr' in device (expected one of: name, type, "
                          "wiring, faults, model, description, command_port, idle_power, busy_power, commands, group)",
                          "cell.yaml:26:35: error[C010]: 'duration': '1' needs a unit: expected a duration (e.g. 2 s, "
                          "150 ms)",
                          "cell.yaml:31:13: error[C030]: no port of 'Lock3' matches a variable under 'MAIN.nothing' "
                          "(expected e.g. MAIN.nothing.programNumber)",
                          "cell.yaml:32:1: error[C011]: unknown key 'extra' in the cell file (expected one of: name, plc, "
                          "run, zones, world, devices, modbus, hmi, plan, extends, replace_devices)"));
}

// Regression test (found by the cell/sim test suite).
TEST_F(LoaderErrors, DeviceMistakesAreReportedEvenWhenThePlcPartFails) {
  write("broken.st", "PROGRAM MAIN\nx := 1;\nEND_PROGRAM\n");
  const std::string devices = "devices:\n  - name: Gizmo\n    type: teleporter\n";
  const std::string unknownType =
      "error[C010]: unknown device type 'teleporter' (expected one of: robot, axis, press, timed, conveyor, sensor, "
      "tank, valve, pump, heater, level_switch, temperature_sensor, g120, "
      "powerflex525, powerflex750, s120_epos)";
  {
    SCOPED_TRACE("no plc section");
    auto found = fails("name: x\n" + devices);
    EXPECT_THAT(found, ::testing::Contains("cell.yaml:4:11: " + unknownType));
  }
  {
    SCOPED_TRACE("unreadable ST source");
    auto found = fails("name: x\nplc:\n  sources: [missing.st]\n" + devices);
    EXPECT_THAT(found, ::testing::Contains("cell.yaml:6:11: " + unknownType));
  }
  {
    SCOPED_TRACE("plc.cycle_time without unit");
    auto found = fails("name: x\nplc:\n  sources: [main.st]\n  cycle_time: 10\n" + devices);
    EXPECT_THAT(found, ::testing::Contains("cell.yaml:7:11: " + unknownType));
  }
  {
    SCOPED_TRACE("ST compile error");
    auto found = fails("name: x\nplc:\n  sources: [broken.st]\n" + devices);
    EXPECT_THAT(found, ::testing::Contains("cell.yaml:6:11: " + unknownType));
  }
}

// Regression: a device entry with a parameter mistake was dropped before its wiring was checked,
// so a wiring mistake of the same device was reported only in a second run (docs/cell-file.md:
// all mistakes of a file in one run).
TEST_F(LoaderErrors, WiringOfADeviceWithAParameterMistakeIsStillChecked) {
  EXPECT_THAT(fails(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n"
                                "    busy_power: 5 mm\n") +
                    kClampParams +
                    "    wiring:\n"
                    "      done: MAIN.dnoe\n"),
              ElementsAre("cell.yaml:7:17: error[C010]: 'busy_power': '5 mm' is not a power (e.g. 150 W)",
                          "cell.yaml:11:13: error[C032]: the PLC has no variable 'MAIN.dnoe' to wire to Clamp.done"));
}

// The same for a drive, whose ports follow its parameters (PCS7_3 exists in telegram 352 only).
TEST_F(LoaderErrors, WiringOfADriveWithAParameterMistakeIsStillChecked) {
  EXPECT_THAT(fails("name: x\n"
                    "plc:\n"
                    "  sources: [main.st]\n"
                    "devices:\n"
                    "  - name: Spindle\n"
                    "    type: g120\n"
                    "    telegram: 352\n"
                    "    p1120: -1 s\n"
                    "    wiring:\n"
                    "      PCS7_3: MAIN.nowhere\n"),
              ElementsAre("cell.yaml:8:12: error[C010]: 'p1120' must be a time greater than 0",
                          "cell.yaml:10:15: error[C032]: the PLC has no variable 'MAIN.nowhere' to wire to Spindle.PCS7_3"));
}

// Regression test (found by the cell/sim test suite).
TEST_F(LoaderErrors, RecordOfAStructureIsAnError) {
  auto found = fails("name: x\n"
                     "plc:\n"
                     "  sources: [main.st]\n"
                     "run:\n"
                     "  record: [MAIN.count, MAIN.Clamp]\n"
                     "devices: []\n");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].rfind("cell.yaml:5:24: error[C0", 0), 0u) << found[0];
  EXPECT_NE(found[0].find("'MAIN.Clamp'"), std::string::npos) << found[0];
}

// Regression test (found by the cell/sim test suite).
TEST_F(LoaderErrors, NonPositiveCycleTimeTimeLimitAndCyclesAreErrors) {
  struct Case {
    const char* plc;
    const char* run;
    const char* at;
    const char* key;
  };
  for (const Case& k : {Case{"  cycle_time: 0 s\n", "", "cell.yaml:4:15: error[C0", "'cycle_time'"},
                        Case{"  cycle_time: -10 ms\n", "", "cell.yaml:4:15: error[C0", "'cycle_time'"},
                        Case{"  cycle_time: 0.1 ns\n", "", "cell.yaml:4:15: error[C0", "'cycle_time'"},
                        Case{"", "  time_limit: -5 s\n", "cell.yaml:5:15: error[C0", "'time_limit'"},
                        Case{"", "  cycles: -1\n", "cell.yaml:5:11: error[C0", "'cycles'"}}) {
    SCOPED_TRACE(std::string(k.plc) + k.run);
    auto found = fails(std::string("name: x\nplc:\n  sources: [main.st]\n") + k.plc + "run:\n" + k.run +
                       "  cycle_done: MAIN.finished\ndevices: []\n");
    EXPECT_EQ(found.size(), 1u);
    if (found.empty()) continue;
    EXPECT_EQ(found[0].rfind(k.at, 0), 0u) << found[0];
    EXPECT_NE(found[0].find(k.key), std::string::npos) << found[0];
  }
}

}  // namespace
}  // namespace virtcom::cell::test
