#pragma once
// A temporary directory for history databases and a small synthetic run recorded tick by tick,
// as sim::Simulation drives a TraceSink: changes, then tick() with the trace as the tick left it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/trace.hpp"
#include "history/recorder.hpp"

namespace virtcom::history::test {

class HistoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / ("virtcom-history-" + std::string(info->test_suite_name()) + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Signals: 0 Press.busy (BOOL), 1 MAIN.count (DINT), 2 Axis.pos (LREAL). Devices Press and
  // Axis; 10 ticks of 1 ms: busy toggles every tick, count counts, a press stroke per 3 ticks,
  // an axis move still running at the end, a collision at 4 ms, a fault with a long message
  // at 7 ms, a cycle at 5 ms and 9 ms.
  static Trace sampleTrace() {
    Trace t;
    t.signals = {{"Press.busy", ElemType::Bool, 0}, {"MAIN.count", ElemType::Dint, 5}, {"Axis.pos", ElemType::Lreal, 0}};
    t.addDevice("Press", "press", "");
    t.addDevice("Axis", "axis", "Axes");
    t.internLabel("Stroke");
    t.internLabel("MoveTo");
    t.internLabel("Zone A");
    return t;
  }

  // Records sampleTrace()'s run into `recorder`; returns the trace as it ended.
  static Trace recordSample(Recorder& recorder) {
    Trace t = sampleTrace();
    recorder.begin(t);
    uint32_t stroke = 0;
    for (int64_t tick = 1; tick <= 10; ++tick) {
      const int64_t now = tick * 1'000'000;
      auto change = [&](TagId tag, uint64_t raw) {
        SignalChange c{now, tag, raw};
        t.changes.push_back(c);
        recorder.change(c);
      };
      change(0, static_cast<uint64_t>(tick % 2));
      change(1, static_cast<uint64_t>(5 + tick));
      if (tick % 3 == 1) stroke = t.beginActivity(0, 0, now);
      if (tick % 3 == 0) t.endActivity(stroke, now, 1.5 * static_cast<double>(tick), tick == 9 ? 42 : 0);
      if (tick == 2) t.beginActivity(1, 1, now);
      if (tick == 4) t.collisions.push_back({now, 2, 0, 1, 0, 1});
      if (tick == 7) t.faults.push_back({now, "Press", std::string(100, 'x') + " overload at station 3"});
      if (tick == 5 || tick == 9) {
        t.cycleStartNs = t.cycleEndNs;
        t.cycleEndNs = now;
        ++t.cyclesCompleted;
      }
      recorder.tick(t, now);
    }
    t.endNs = 10'000'000;
    t.end = RunEnd::TimeLimit;
    t.endMessage = "time limit reached";
    t.totals = {{6'000'000, 30.5}, {8'000'000, 12.25}};
    recorder.end(t);
    return t;
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace virtcom::history::test
