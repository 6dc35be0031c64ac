// A cell whose controller is external (no soft PLC): bridges drive the command signals and see
// the status after the devices stepped, in virtual time; a failing bridge ends the run.
#include <gtest/gtest.h>

#include "sim_rig.hpp"

namespace virtcom::sim::test {
namespace {

constexpr const char* kClampCell = R"(plc:
  cycle_time: 5 ms
run:
  time_limit: 2 s
devices:
  - name: Clamp
    type: timed
    commands:
      1: { name: Close, duration: 100 ms }
)";

// Plays the external PLC's part of the handshake: command 1 from 50 ms, execute until done.
class ScriptedPlc final : public BusBridge {
 public:
  explicit ScriptedPlc(const TagBus& bus)
      : program_(bus.find("Clamp.programNumber")), execute_(bus.find("Clamp.execute")), done_(bus.find("Clamp.done")) {}
  bool pull(TagBus& bus, int64_t nowNs) override {
    ++pulls_;
    if (failAtNs_ >= 0 && nowNs >= failAtNs_) return false;
    bus.setInt(program_, 1);
    bus.setBool(execute_, nowNs >= 50 * kMs && doneAtNs_ < 0);
    return true;
  }
  void push(const TagBus& bus, int64_t nowNs) override {
    if (bus.getBool(done_) && doneAtNs_ < 0) doneAtNs_ = nowNs;
  }
  std::string failure() const override { return "link lost"; }

  TagId program_, execute_, done_;
  int64_t doneAtNs_ = -1;
  int64_t failAtNs_ = -1;
  int pulls_ = 0;
};

class ExternalController : public SimFiles {};

TEST_F(ExternalController, BridgesDriveTheDevicesAtTheCellsCycleTime) {
  auto run = loadCell(kClampCell, {});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->cell->module, nullptr);
  ScriptedPlc plc(run->cell->bus);
  SimOptions options;
  options.bridges.push_back(&plc);
  EXPECT_EQ(run->run(options), RunEnd::TimeLimit);
  EXPECT_EQ(plc.pulls_, 401);  // ticks at 0, 5 ms, ..., 2 s
  EXPECT_EQ(plc.doneAtNs_, 150 * kMs);  // execute seen in the tick it was pulled, 100 ms of work
  ASSERT_EQ(run->trace().activities.size(), 1u);
  EXPECT_EQ(run->trace().activities[0].startNs, 50 * kMs);
}

TEST_F(ExternalController, AFailingBridgeEndsTheRunAsAPlcFault) {
  auto run = loadCell(kClampCell, {});
  ASSERT_TRUE(run);
  ScriptedPlc plc(run->cell->bus);
  plc.failAtNs_ = 20 * kMs;
  SimOptions options;
  options.bridges.push_back(&plc);
  EXPECT_EQ(run->run(options), RunEnd::PlcFault);
  EXPECT_EQ(run->trace().endMessage, "link lost");
  ASSERT_EQ(run->trace().faults.size(), 1u);
  EXPECT_EQ(run->trace().faults[0].timeNs, 20 * kMs);
}

// The external PLC's cycle marker arrives on a tag (as the ADS bridge reads `run: cycle_done`):
// its rising edges count cycles and end the run; a marker set before the run is no edge.
class CycleMarker final : public BusBridge {
 public:
  explicit CycleMarker(TagId tag) : tag_(tag) {}
  bool pull(TagBus& bus, int64_t nowNs) override {
    bus.setBool(tag_, nowNs < 20 * kMs || (nowNs >= 300 * kMs && nowNs < 320 * kMs) || nowNs >= 700 * kMs);
    return true;
  }
  void push(const TagBus&, int64_t) override {}
  void simulationStopped() override { ++stops_; }
  TagId tag_;
  int stops_ = 0;
};

TEST_F(ExternalController, CyclesAreCountedOnTheExternalPlcsMarkerTag) {
  auto run = loadCell(kClampCell, {});
  ASSERT_TRUE(run);
  run->cell->run.cycleDoneTag = run->cell->bus.add("MAIN.cycleDone", ElemType::Bool);
  run->cell->run.cycles = 2;
  CycleMarker plc(run->cell->run.cycleDoneTag);
  SimOptions options;
  options.bridges.push_back(&plc);
  EXPECT_EQ(run->run(options), RunEnd::Completed);
  EXPECT_EQ(run->trace().cyclesCompleted, 2u);
  EXPECT_EQ(run->trace().cycleStartNs, 300 * kMs);
  EXPECT_EQ(run->trace().cycleEndNs, 700 * kMs);
  EXPECT_EQ(run->trace().endNs, 700 * kMs);
  EXPECT_EQ(plc.stops_, 1);  // told once that the run ended
}

}  // namespace
}  // namespace virtcom::sim::test
