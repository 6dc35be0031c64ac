#pragma once
// Writes a scenario file for the station cell (tests/e2e/data/scenarios/station) into a
// per-test temporary folder and runs it as `virtcom test` would, one case.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scenario/runner.hpp"

namespace virtcom::scenario::test {

inline std::string stationCell() { return std::string(VIRTCOM_SOURCE_DIR) + "/tests/e2e/data/scenarios/station/cell.yaml"; }

class ScenarioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("virtcom-scenario-" + std::to_string(getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Writes `body` (the scenario without its `cell:` line) as test.yaml; returns its path.
  std::string write(const std::string& body, const std::string& name = "test.yaml") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << "cell: " << stationCell() << "\n" << body;
    return path;
  }
  CaseResult run(const std::string& body, size_t row = SIZE_MAX) {
    CaseSpec spec{write(body), row, "test", "test"};
    return runCase(spec, {});
  }
  // The first line of an ERROR result's diagnostics, with the temporary folder cut off.
  std::string firstDiagnostic(const CaseResult& r) const {
    if (r.messages.empty()) return "";
    std::string line = r.messages[0].substr(0, r.messages[0].find('\n'));
    const std::string dir = dir_.string() + "/";
    if (line.starts_with(dir)) line.erase(0, dir.size());
    return line;
  }
  // Every message of the result, one string.
  static std::string text(const CaseResult& r) {
    std::string all;
    for (const auto& m : r.messages) all += m + "\n";
    return all;
  }

  std::filesystem::path dir_;
};

}  // namespace virtcom::scenario::test
