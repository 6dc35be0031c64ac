// Drive devices from cell-file entries: parameters, diagnostics with file:line:col, ports
// named like the telegram words, fault and comm-loss injection through step() and the tag bus.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "cell/yaml_config.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "core/trace.hpp"
#include "drives/drive_messages.hpp"
#include "drives/drive_registry.hpp"
#include "drives/speed_axis.hpp"

namespace virtcom::drives {
namespace {

struct Loaded {
  SourceManager sources;
  Diagnostics diags;
  ConfigNode root;
  Trace trace;
  plant::World world{trace};
  TagBus bus;
  std::unique_ptr<plant::Device> device;
  int64_t nowNs = 0;

  explicit Loaded(const std::string& yaml) {
    if (!cell::parseYaml("drive.yaml", yaml, sources, diags, root)) return;
    ConfigReader cfg(root, diags, "device");
    const std::string type = cfg.requireString("type");
    const ConfigNode* faults = cfg.child("faults");
    device = plant::createDevice(type, "Drive1", cfg, world, deviceTypes());
    if (diags.hasErrors()) device = nullptr;  // a device with parameter mistakes must not run
    if (!device) return;
    if (faults) {
      ConfigReader f(*faults, diags, "'faults'");
      device->readFaults(f);
      f.rejectUnknownKeys();
    }
    for (size_t i = 0; i < device->ports().size(); ++i)
      device->bindPort(i, bus.add("Drive1." + device->ports()[i].name, device->ports()[i].type));
    device->prepare(world, trace);
  }
  std::string errors() const {
    return diags.render(sources);
  }
  TagId tag(const std::string& port) const { return device->tag(static_cast<size_t>(device->portIndex(port))); }
  void stepFor(int64_t ms, int64_t cycleMs = 2) {
    for (int64_t t = 0; t < ms; t += cycleMs) {
      nowNs += cycleMs * 1'000'000;
      device->step(plant::StepContext{nowNs, cycleMs * 1'000'000, bus, world, trace});
    }
  }
};

TEST(DriveConfig, G120PortsAreTheTelegramWords) {
  Loaded l("type: g120\ntelegram: 352\np2000: 1500\n");
  ASSERT_NE(l.device, nullptr) << l.errors();
  EXPECT_EQ(l.device->portIndex("STW1"), 0);
  EXPECT_EQ(l.device->ports()[1].type, ElemType::Int);          // NSOLL_A
  EXPECT_EQ(l.device->ports()[0].dir, plant::PortDir::In);
  EXPECT_EQ(l.device->ports()[6].name, "ZSW1");
  EXPECT_EQ(l.device->ports()[6].dir, plant::PortDir::Out);
  EXPECT_GE(l.device->portIndex("FAULT_CODE"), 0);
  EXPECT_GE(l.device->portIndex("position"), 0);
}

TEST(DriveConfig, ReportsWrongValuesWithTheirPosition) {
  Loaded l("type: g120\ntelegram: 2\np1120: -1 s\ncomm_fault: F1\nload: {gear: 3}\n");
  EXPECT_EQ(l.device, nullptr);
  const std::string e = l.errors();
  EXPECT_NE(e.find("drive.yaml:2:11"), std::string::npos) << e;
  EXPECT_NE(e.find("must be 1 or 352"), std::string::npos) << e;
  EXPECT_NE(e.find("'p1120' must be a time greater than 0"), std::string::npos) << e;
  EXPECT_NE(e.find("'comm_fault' must be F01910"), std::string::npos) << e;
  EXPECT_NE(e.find("gear"), std::string::npos) << e;
}

TEST(DriveConfig, DelayAndMopKeysReportWrongValues) {
  Loaded g("type: g120\np2166: -1 s\np2164: -2\np1227: 0 s\np1047: 0 s\nmop: true\n");
  EXPECT_EQ(g.device, nullptr);
  EXPECT_NE(g.errors().find("'p2166' must be a time of 0 or more"), std::string::npos) << g.errors();
  EXPECT_NE(g.errors().find("drive.yaml:3:8"), std::string::npos) << g.errors();
  EXPECT_NE(g.errors().find("'p2164' must be a number of 0 or more"), std::string::npos) << g.errors();
  EXPECT_NE(g.errors().find("'p1227' must be a time greater than 0"), std::string::npos) << g.errors();
  EXPECT_NE(g.errors().find("'p1047' must be a time greater than 0"), std::string::npos) << g.errors();
  EXPECT_NE(Loaded("type: g120\np2166: 0 s\nmop: true\np1040: 100\np1030: 1\n").device, nullptr);
  Loaded start("type: g120\nmop: true\np1040: 2000\np1030: 6\n");
  EXPECT_NE(start.errors().find("'p1040' (MOP start value) must not exceed p1082"), std::string::npos) << start.errors();
  EXPECT_NE(start.errors().find("drive.yaml:4:8"), std::string::npos) << start.errors();
  EXPECT_NE(start.errors().find("'p1030' (MOP configuration) must be 0"), std::string::npos) << start.errors();
  Loaded p("type: powerflex525\nmop: true\na430: 0 s\na428: 2\na429: -1\n");
  EXPECT_NE(p.errors().find("'a430' must be a time greater than 0"), std::string::npos) << p.errors();
  EXPECT_NE(p.errors().find("drive.yaml:4:7"), std::string::npos) << p.errors();
  EXPECT_NE(p.errors().find("'a428' (MOP Reset Sel) must be 0 (Zero MOP Ref"), std::string::npos) << p.errors();
  EXPECT_NE(p.errors().find("'a429' (MOP Preload) must be 0 (no preload)"), std::string::npos) << p.errors();
  EXPECT_NE(Loaded("type: powerflex525\nmop: true\na428: 0\na429: 1\n").device, nullptr);
  Loaded m("type: powerflex750\ncontrol_mode: torque\n");
  EXPECT_NE(m.errors().find("'control_mode' must be speed or position, not 'torque'"), std::string::npos) << m.errors();
  Loaded u("type: powerflex750\ncontrol_mode: position\nspeed_units: rpm\n");
  EXPECT_NE(u.errors().find("'speed_units' does not apply"), std::string::npos) << u.errors();
}

// One reader for every drive's injection codes; the family says whose codes it accepts.
TEST(DriveConfig, EachDriveFamilyInjectsItsOwnCodes) {
  auto fault = drives::parseInjectionCode(drives::MessageFamily::Sinamics, "F07900");
  ASSERT_TRUE(fault);
  EXPECT_EQ(fault->kind, drives::MessageKind::Fault);
  EXPECT_EQ(fault->number, 7900);
  EXPECT_EQ(fault->reaction, drives::Reaction::Off2);
  auto alarm = drives::parseInjectionCode(drives::MessageFamily::Sinamics, "A01920");
  ASSERT_TRUE(alarm);
  EXPECT_EQ(alarm->kind, drives::MessageKind::Alarm);
  EXPECT_EQ(alarm->number, 1920);
  for (const char* code : {"F4", "4"}) {
    auto powerFlex = drives::parseInjectionCode(drives::MessageFamily::PowerFlex, code);
    ASSERT_TRUE(powerFlex) << code;
    EXPECT_EQ(powerFlex->kind, drives::MessageKind::Fault);
    EXPECT_EQ(powerFlex->number, 4);
    EXPECT_EQ(powerFlex->reaction, drives::Reaction::None);
  }
  EXPECT_EQ(drives::parseInjectionCode(drives::MessageFamily::PowerFlex, "F07900").error().rfind("'F07900' is not a PowerFlex fault number (expected F and one of: 2, 3, 4", 0), 0u);
  EXPECT_EQ(drives::parseInjectionCode(drives::MessageFamily::Sinamics, "F4").error().rfind("'F4' is not a known SINAMICS fault or alarm (expected one of: F01000, F01001", 0), 0u);
  Loaded epos("type: s120_epos\nfaults:\n  inject:\n    - {code: F4}\n");
  EXPECT_NE(epos.errors().find("'F4' is not a known SINAMICS fault or alarm"), std::string::npos) << epos.errors();
}

TEST(DriveConfig, UnknownInjectionCodesListTheCatalogue) {
  Loaded g("type: g120\nfaults:\n  inject:\n    - {code: F99999, at: 1 s}\n");
  EXPECT_NE(g.errors().find("'F99999' is not a known SINAMICS fault or alarm (expected one of: F01000"), std::string::npos)
      << g.errors();
  Loaded p("type: powerflex525\nfaults:\n  inject:\n    - {code: F1}\n");
  EXPECT_NE(p.errors().find("'F1' is not a PowerFlex fault number"), std::string::npos) << p.errors();
  Loaded c("type: powerflex525\nc143: explode\n");
  EXPECT_NE(c.errors().find("'c143' (comm loss action) must be fault, stop or hold_last"), std::string::npos) << c.errors();
  EXPECT_EQ(Loaded("type: robotdrive\n").errors().find("powerflex525") != std::string::npos, true);
}

TEST(DriveConfig, InjectedFaultRaisesAndIsAcknowledgedThroughTheBus) {
  Loaded l("type: g120\nfaults:\n  inject:\n    - {code: F07900, at: 1 s, duration: 100 ms}\n");
  ASSERT_NE(l.device, nullptr) << l.errors();
  l.bus.setInt(l.tag("STW1"), 0x047E);
  l.stepFor(10);
  l.bus.setInt(l.tag("STW1"), 0x047F);
  l.bus.setInt(l.tag("NSOLL_A"), 0x2000);
  l.stepFor(900);
  EXPECT_EQ(l.bus.getInt(l.tag("ZSW1")) & 0x7F, 0x37);
  l.stepFor(200);
  EXPECT_TRUE(l.bus.getInt(l.tag("ZSW1")) & 0x08);  // F07900, OFF2: coasting in S1
  ASSERT_EQ(l.trace.faults.size(), 1u);
  EXPECT_EQ(l.trace.faults[0].message, "F07900");
  l.bus.setInt(l.tag("STW1"), 0x04FF);
  l.stepFor(2);
  EXPECT_FALSE(l.bus.getInt(l.tag("ZSW1")) & 0x08);
  EXPECT_GT(l.bus.getReal(l.tag("speed")), 0.0);      // still coasting
}

TEST(DriveConfig, InjectedAlarmAtSpeedShowsInWarnCode) {
  Loaded l("type: g120\ntelegram: 352\nfaults:\n  inject:\n    - {code: A05000, at_speed_rpm: 600, duration: 500 ms}\n");
  ASSERT_NE(l.device, nullptr) << l.errors();
  l.bus.setInt(l.tag("STW1"), 0x047E);
  l.stepFor(10);
  l.bus.setInt(l.tag("STW1"), 0x047F);
  l.bus.setInt(l.tag("NSOLL_A"), 0x2000);
  l.stepFor(400);
  EXPECT_EQ(l.bus.getInt(l.tag("WARN_CODE")), 0);     // 270 rpm so far
  l.stepFor(600);
  EXPECT_EQ(l.bus.getInt(l.tag("WARN_CODE")), 5000);
  l.stepFor(600);
  EXPECT_EQ(l.bus.getInt(l.tag("WARN_CODE")), 0);
}

TEST(DriveConfig, CommLossWindowStopsTheFrames) {
  Loaded l("type: powerflex525\np041: 1 s\nfaults:\n  comm_loss:\n    - {at: 1 s, duration: 200 ms}\n");
  ASSERT_NE(l.device, nullptr) << l.errors();
  l.bus.setInt(l.tag("LogicCommand"), 0x0012);
  l.bus.setInt(l.tag("FreqCommand"), 1000);
  l.stepFor(990);
  EXPECT_EQ(l.bus.getInt(l.tag("OutputFreq")), 1000);
  l.stepFor(150);
  EXPECT_TRUE(l.bus.getInt(l.tag("LogicStatus")) & 0x80);
  EXPECT_GT(l.bus.getReal(l.tag("position")), 5.0) << "no load lead: position in revolutions";
}

}  // namespace
}  // namespace virtcom::drives
