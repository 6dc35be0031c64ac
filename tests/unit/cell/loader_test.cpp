// The happy path of the cell loader: every device port becomes a tag named `Device.port` of the
// port's type, wires run in the port's direction (input ports PLC -> tag, output ports tag ->
// PLC), prefix wiring connects exactly the ports whose variables exist, and the run, plc and
// world sections land in the Cell.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "cell_files.hpp"
#include "core/value_codec.hpp"

namespace virtcom::cell::test {
namespace {

class Loader : public CellFiles {
 protected:
  void SetUp() override {
    CellFiles::SetUp();
    write("main.st", kMainSt);
  }
  // Loads cell.yaml = `text`; the load must succeed without any diagnostic.
  std::unique_ptr<Cell> loads(const std::string& text) {
    auto cell = CellFiles::loads(text);
    EXPECT_EQ(diags_.all().size(), 0u) << rendered();
    return cell;
  }
  static const Wire* wireTo(const Cell& cell, const std::string& var) {
    for (const auto& w : cell.wires)
      if (w.varName == var) return &w;
    return nullptr;
  }
};

const char* const kTwoDevices = R"(name: tiny
plc:
  sources: [main.st]
  cycle_time: 5 ms
run:
  cycle_done: MAIN.finished
  cycles: 3
  time_limit: 20 s
  stop_on_collision: false
  record: [MAIN.count]
world:
  facts:
    partPresent: true
    clampClosed: false
devices:
  - name: Clamp
    type: timed
    commands:
      1: { name: Close, duration: 1 s, requires: [partPresent], sets: [clampClosed] }
    wiring:
      programNumber: MAIN.cmd
      execute: MAIN.exec
      done: MAIN.done
      error: MAIN.err
      busy: MAIN.busy
  - name: Lock
    type: timed
    commands:
      1: { name: Lock, duration: 200 ms }
    wiring: MAIN.Clamp
)";

TEST_F(Loader, PortsBecomeTagsNamedDeviceDotPort) {
  auto cell = loads(kTwoDevices);
  ASSERT_NE(cell, nullptr);
  ASSERT_EQ(cell->devices.size(), 2u);
  EXPECT_EQ(cell->devices[0]->name(), "Clamp");
  EXPECT_EQ(cell->devices[1]->name(), "Lock");
  std::vector<std::string> names;
  for (TagId id = 0; id < cell->bus.size(); ++id) names.push_back(cell->bus.name(id));
  EXPECT_THAT(names, ::testing::ElementsAre("Clamp.programNumber", "Clamp.execute", "Clamp.done", "Clamp.error",
                                            "Clamp.busy", "Lock.programNumber", "Lock.execute", "Lock.done",
                                            "Lock.error", "Lock.busy"));
  EXPECT_EQ(cell->bus.type(cell->bus.find("Clamp.programNumber")), ElemType::Int);
  EXPECT_EQ(cell->bus.type(cell->bus.find("Clamp.execute")), ElemType::Bool);
  EXPECT_EQ(cell->bus.type(cell->bus.find("Clamp.error")), ElemType::Int);
  // every device's tags are bound to its ports
  for (const auto& d : cell->devices)
    for (size_t i = 0; i < d->ports().size(); ++i) EXPECT_EQ(cell->bus.name(d->tag(i)), d->name() + "." + d->ports()[i].name);
}

TEST_F(Loader, WiresRunInThePortsDirection) {
  auto cell = loads(kTwoDevices);
  ASSERT_NE(cell, nullptr);
  ASSERT_EQ(cell->wires.size(), 10u);
  struct Expect {
    const char* var;
    const char* tag;
    plant::PortDir dir;
  };
  const Expect expected[] = {
      {"MAIN.cmd", "Clamp.programNumber", plant::PortDir::In},  {"MAIN.exec", "Clamp.execute", plant::PortDir::In},
      {"MAIN.done", "Clamp.done", plant::PortDir::Out},         {"MAIN.err", "Clamp.error", plant::PortDir::Out},
      {"MAIN.busy", "Clamp.busy", plant::PortDir::Out},
      {"MAIN.Clamp.programNumber", "Lock.programNumber", plant::PortDir::In},
      {"MAIN.Clamp.execute", "Lock.execute", plant::PortDir::In},
      {"MAIN.Clamp.done", "Lock.done", plant::PortDir::Out},
      {"MAIN.Clamp.error", "Lock.error", plant::PortDir::Out},
      {"MAIN.Clamp.busy", "Lock.busy", plant::PortDir::Out},
  };
  for (const auto& e : expected) {
    SCOPED_TRACE(e.var);
    const Wire* w = wireTo(*cell, e.var);
    ASSERT_NE(w, nullptr);
    EXPECT_EQ(cell->bus.name(w->tag), e.tag);
    EXPECT_EQ(w->dir, e.dir);
    auto ref = bc::resolveVariable(*cell->module, e.var);
    ASSERT_TRUE(ref.has_value());
    EXPECT_EQ(w->address, ref->address);
  }
}

TEST_F(Loader, WiresMoveValuesBetweenMemoryAndBus) {
  auto cell = loads(kTwoDevices);
  ASSERT_NE(cell, nullptr);
  std::vector<uint8_t> memory(cell->module->memorySize(), 0);
  // input port: PLC variable -> tag
  const Wire* cmd = wireTo(*cell, "MAIN.cmd");
  ASSERT_NE(cmd, nullptr);
  int16_t seven = 7;
  std::memcpy(memory.data() + cmd->address, &seven, 2);
  loadVariable(memory.data() + cmd->address, cmd->bit, cmd->varType, cell->bus, cmd->tag);
  EXPECT_EQ(cell->bus.getInt(cell->bus.find("Clamp.programNumber")), 7);
  // output port: tag -> PLC variable, reporting whether the bytes changed
  const Wire* err = wireTo(*cell, "MAIN.err");
  ASSERT_NE(err, nullptr);
  cell->bus.setInt(cell->bus.find("Clamp.error"), 10);
  EXPECT_TRUE(storeVariable(memory.data() + err->address, err->bit, err->varType, cell->bus, err->tag));
  EXPECT_FALSE(storeVariable(memory.data() + err->address, err->bit, err->varType, cell->bus, err->tag));
  int16_t code = 0;
  std::memcpy(&code, memory.data() + err->address, 2);
  EXPECT_EQ(code, 10);
}

TEST_F(Loader, PrefixWiringConnectsOnlyThePortsThatExist) {
  auto cell = loads(std::string("name: x\n"
                                "plc:\n"
                                "  sources: [main.st]\n"
                                "devices:\n"
                                "  - name: Clamp\n"
                                "    type: timed\n") +
                    kClampParams + "    wiring: MAIN.Part\n");
  ASSERT_NE(cell, nullptr);
  ASSERT_EQ(cell->wires.size(), 2u);
  EXPECT_EQ(cell->wires[0].varName, "MAIN.Part.execute");
  EXPECT_EQ(cell->wires[0].dir, plant::PortDir::In);
  EXPECT_EQ(cell->wires[1].varName, "MAIN.Part.done");
  EXPECT_EQ(cell->wires[1].dir, plant::PortDir::Out);
  // unwired ports are still tags
  EXPECT_NE(cell->bus.find("Clamp.busy"), kNoTag);
}

TEST_F(Loader, RunPlcAndWorldSettings) {
  auto cell = loads(kTwoDevices);
  ASSERT_NE(cell, nullptr);
  EXPECT_EQ(cell->name, "tiny");
  EXPECT_EQ(cell->run.plcCycleNs, 5'000'000);
  EXPECT_EQ(cell->run.timeLimitNs, 20'000'000'000);
  EXPECT_EQ(cell->run.cycleDoneVar, "MAIN.finished");
  EXPECT_EQ(cell->run.cycles, 3u);
  EXPECT_FALSE(cell->run.stopOnCollision);
  EXPECT_TRUE(cell->run.stopOnDeviceError);
  EXPECT_THAT(cell->run.recordVars, ::testing::ElementsAre("MAIN.count"));
  EXPECT_FALSE(cell->run.until.valid);
  EXPECT_TRUE(cell->world.hasFact(cell->world.fact("partPresent")));
  EXPECT_FALSE(cell->world.hasFact(cell->world.fact("clampClosed")));
  // the default task runs at plc.cycle_time
  bool found = false;
  for (const auto& t : cell->module->tasks)
    if (t.name == "MainTask") {
      found = true;
      EXPECT_EQ(t.intervalNs, 5'000'000);
    }
  EXPECT_TRUE(found);
}

// The program's own CONFIGURATION: `p1` has no WITH, so the compiler runs it in its implicit
// `__DEFAULT` task, which takes plc.cycle_time like `MainTask` does; a declared TASK keeps its
// INTERVAL, even one named MainTask.
const char* const kConfiguredSt = R"st(
PROGRAM P1
VAR runs : INT; END_VAR
runs := runs + 1;
END_PROGRAM

PROGRAM P2
VAR runs : INT; END_VAR
runs := runs + 1;
END_PROGRAM

CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK MainTask(INTERVAL := T#30ms, PRIORITY := 2);
    PROGRAM p1 : P1;
    PROGRAM p2 WITH MainTask : P2;
  END_RESOURCE
END_CONFIGURATION
)st";

TEST_F(Loader, PlcCycleTimeAppliesToTheImplicitDefaultTaskOfAConfiguration) {
  write("configured.st", kConfiguredSt);
  auto cell = loads("name: configured\nplc:\n  sources: [configured.st]\n  cycle_time: 5 ms\ndevices: []\n");
  ASSERT_NE(cell, nullptr);
  ASSERT_NE(cell->module, nullptr);
  ASSERT_EQ(cell->module->tasks.size(), 2u);
  const bc::TaskInfo& implicit = cell->module->tasks[0];
  EXPECT_EQ(implicit.name, "__DEFAULT");
  EXPECT_TRUE(implicit.isDefault);
  EXPECT_EQ(implicit.intervalNs, 5'000'000) << "the implicit task runs at plc.cycle_time";
  const bc::TaskInfo& declared = cell->module->tasks[1];
  EXPECT_EQ(declared.name, "MainTask");
  EXPECT_FALSE(declared.isDefault);
  EXPECT_EQ(declared.intervalNs, 30'000'000) << "a declared TASK keeps its INTERVAL";
}

// `extends`: the sections this file lacks (devices, world, plc) come from the base file; its
// own sections (name, run) replace the base's.
TEST_F(Loader, ExtendsTakesTheSectionsTheFileLacksFromTheBase) {
  write("base.yaml", kTwoDevices);
  auto cell = loads("extends: base.yaml\nname: variant\nrun:\n  cycle_done: MAIN.done\n");
  ASSERT_NE(cell, nullptr);
  EXPECT_EQ(cell->name, "variant");
  EXPECT_EQ(cell->run.cycleDoneVar, "MAIN.done");
  EXPECT_EQ(cell->run.cycles, 1u) << "run is this file's, not merged with the base's";
  EXPECT_EQ(cell->run.plcCycleNs, 5'000'000);
  ASSERT_EQ(cell->devices.size(), 2u);
  EXPECT_TRUE(cell->world.hasFact(cell->world.fact("partPresent")));
}

// `replace_devices`: a variant swaps single devices of the base's list by name, in their place
// (devices step in file order); the others stay as the base writes them.
TEST_F(Loader, ReplaceDevicesSwapsBaseDevicesByName) {
  write("base.yaml", kTwoDevices);
  auto cell = loads("extends: base.yaml\n"
                    "replace_devices:\n"
                    "  - name: Clamp\n"
                    "    type: axis\n"
                    "    max_speed: 100 mm/s\n"
                    "    acceleration: 1000 mm/s^2\n"
                    "    min_position: 0 mm\n"
                    "    max_position: 100 mm\n");
  ASSERT_NE(cell, nullptr);
  ASSERT_EQ(cell->devices.size(), 2u);
  EXPECT_EQ(cell->devices[0]->name(), "Clamp");
  EXPECT_EQ(cell->devices[0]->type(), "axis");
  EXPECT_EQ(cell->devices[1]->name(), "Lock");
  EXPECT_EQ(cell->devices[1]->type(), "timed");
}

TEST_F(Loader, NameDefaultsToTheFolderName) {
  auto cell = loads("plc:\n  sources: [main.st]\ndevices: []\n");
  ASSERT_NE(cell, nullptr);
  EXPECT_EQ(cell->name, dir_.filename().string());
  EXPECT_EQ(cell->run.plcCycleNs, 10'000'000);
  EXPECT_EQ(cell->run.timeLimitNs, 600'000'000'000);
}

TEST_F(Loader, UntilConditionIsResolved) {
  auto cell = loads("plc:\n  sources: [main.st]\nrun:\n  until: \"MAIN.count >= 3\"\ndevices: []\n");
  ASSERT_NE(cell, nullptr);
  const Condition& c = cell->run.until;
  ASSERT_TRUE(c.valid);
  EXPECT_EQ(c.text, "MAIN.count >= 3");
  EXPECT_EQ(c.op, Condition::Op::Ge);
  EXPECT_EQ(c.value, 3);
  std::vector<uint8_t> memory(cell->module->memorySize(), 0);
  EXPECT_FALSE(evaluate(c, memory.data()));
  int16_t three = 3;
  std::memcpy(memory.data() + c.address, &three, 2);
  EXPECT_TRUE(evaluate(c, memory.data()));
}

TEST_F(Loader, ConditionOperatorsAndBareBool) {
  auto cell = loads("plc:\n  sources: [main.st]\ndevices: []\n");
  ASSERT_NE(cell, nullptr);
  std::vector<uint8_t> memory(cell->module->memorySize(), 0);
  auto ref = bc::resolveVariable(*cell->module, "MAIN.count");
  ASSERT_TRUE(ref.has_value());
  int16_t five = 5;
  std::memcpy(memory.data() + ref->address, &five, 2);
  struct Case {
    const char* text;
    bool holds;
  };
  for (const Case& k : {Case{"MAIN.count = 5", true}, Case{"MAIN.count <> 5", false}, Case{"MAIN.count != 4", true},
                        Case{"MAIN.count < 5", false}, Case{"MAIN.count <= 5", true}, Case{"MAIN.count > 4", true},
                        Case{"MAIN.count>=6", false}, Case{"MAIN.finished", false}, Case{"MAIN.finished = FALSE", true}}) {
    SCOPED_TRACE(k.text);
    Diagnostics d;
    Condition c = parseCondition(*cell->module, k.text, {}, d);
    ASSERT_TRUE(c.valid) << d.render(sources_);
    EXPECT_EQ(evaluate(c, memory.data()), k.holds);
  }
}

}  // namespace
}  // namespace virtcom::cell::test
