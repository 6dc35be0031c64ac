#pragma once
// Helpers for simulation tests: a per-test temporary folder for small cells (cell.yaml + ST), a
// CellRun that owns the loaded cell, its simulation and the rendered reports, and readable
// renderings of a Trace (signal changes and activities as short text lines) so expectations
// read like a timing diagram.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cell/cell.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/waveform.hpp"
#include "sim/simulation.hpp"

namespace virtcom::sim::test {

inline constexpr int64_t kMs = 1'000'000;

inline std::string gearboxCellPath() { return std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell.yaml"; }

// `preset` for SimOptions: NAME=VALUE pairs written after the cold start, before the first scan
// (what `virtcom run --set` does). A bad name or value fails the test.
inline std::function<void(plc::Runtime&)> presets(std::vector<std::pair<std::string, std::string>> values) {
  return [values](plc::Runtime& plc) {
    for (const auto& [name, value] : values) {
      auto ref = bc::resolveVariable(plc.module(), name);
      ASSERT_TRUE(ref.has_value()) << name;
      std::string problem = bc::writeValueFromText(plc.module(), *ref, value, plc.machine().memory());
      ASSERT_EQ(problem, "") << name;
    }
  };
}

// One loaded cell and its run. Not copyable: the simulation points into the cell.
struct CellRun {
  SourceManager sources;
  Diagnostics diags;
  std::unique_ptr<cell::Cell> cell;
  std::unique_ptr<Simulation> simulation;

  // Loads the cell file; false (diagnostics in problems()) if it does not load.
  bool load(const std::string& path) {
    cell = cell::loadCell(path, sources, diags);
    return cell != nullptr;
  }
  std::string problems() const { return diags.render(sources); }
  // Runs to the end (load() must have succeeded).
  RunEnd run(SimOptions options = {}) {
    simulation = std::make_unique<Simulation>(*cell, std::move(options));
    return simulation->run();
  }
  const Trace& trace() const { return cell->trace; }
  report::Kpis kpis() const { return report::computeKpis(cell->trace); }
  // Exactly what `virtcom run --json` / `--csv` write for this run.
  std::string json() const { return report::jsonReport(cell->trace, kpis()); }
  std::string csv() const { return report::csvChanges(cell->trace); }
};

// Loads and runs the gearbox example with MAIN.sequence preset; fails the test if it does not load.
inline std::unique_ptr<CellRun> runGearbox(int sequence, bool skipRepeatedScans = true, bool eventTime = true) {
  auto run = std::make_unique<CellRun>();
  if (!run->load(gearboxCellPath())) {
    ADD_FAILURE() << run->problems();
    return nullptr;
  }
  SimOptions options;
  options.skipRepeatedScans = skipRepeatedScans;
  options.eventTime = eventTime;
  options.preset = presets({{"MAIN.sequence", std::to_string(sequence)}});
  run->run(std::move(options));
  return run;
}

// "1010 ms Clamp.done = 1" (times that are not whole milliseconds are written in ns).
inline std::string timeText(int64_t ns) {
  return ns % kMs == 0 ? std::to_string(ns / kMs) + " ms" : std::to_string(ns) + " ns";
}

inline std::vector<std::string> changesText(const Trace& trace) {
  std::vector<std::string> out;
  for (const auto& c : trace.changes)
    out.push_back(timeText(c.timeNs) + " " + trace.signals[c.tag].name + " = " +
                  std::to_string(static_cast<int64_t>(c.raw)));
  return out;
}

// "Clamp Close 0 ms .. 1000 ms" (".. running" while not ended), with " error 10" if it failed.
inline std::vector<std::string> activitiesText(const Trace& trace) {
  std::vector<std::string> out;
  for (const auto& a : trace.activities) {
    std::string line = trace.devices[a.device].name + " " + trace.labels[a.label] + " " + timeText(a.startNs) + " .. " +
                       (a.endNs < 0 ? std::string("running") : timeText(a.endNs));
    if (a.errorCode != 0) line += " error " + std::to_string(a.errorCode);
    out.push_back(line);
  }
  return out;
}

// A per-test temporary folder for cell files.
class SimFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("virtcom_sim_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream out(dir_ / name, std::ios::binary);
    out << text;
  }
  // Writes cell.yaml (and the ST files given) and loads it; fails the test if it does not load.
  std::unique_ptr<CellRun> loadCell(const std::string& yaml, const std::vector<std::pair<std::string, std::string>>& st) {
    for (const auto& [name, text] : st) write(name, text);
    write("cell.yaml", yaml);
    auto run = std::make_unique<CellRun>();
    if (!run->load((dir_ / "cell.yaml").string())) {
      ADD_FAILURE() << stripDir(run->problems());
      return nullptr;
    }
    return run;
  }
  std::string stripDir(std::string text) const {
    const std::string prefix = dir_.string() + "/";
    for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at)) text.erase(at, prefix.size());
    return text;
  }

  std::filesystem::path dir_;
};

}  // namespace virtcom::sim::test
