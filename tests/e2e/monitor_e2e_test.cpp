// End-to-end: `virtcom monitor` watching a plant without a real one. `virtcom serve
// examples/ads-cell/cell.yaml --ads` in a second process plays the plant (its soft PLC and
// simulated devices, served over ADS); the monitor reads the same cell's wiring from it and
// must see the served run's own operations: per device the same operations in the same order,
// with the same errors. Durations are not compared here (two processes paced by a shared,
// loaded machine); tests/unit/sim/operation_recogniser_test.cpp compares them exactly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/loopback_client.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::LoopbackClient;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kExample = std::string(VIRTCOM_SOURCE_DIR) + "/examples/ads-cell";

class Monitor : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("virtcom_monitor_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

// Per device, its completed operations in order: "Lock", "PressPin error 40", ...
using Operations = std::map<std::string, std::vector<std::string>>;

// The completed activities of a JSON report, by device; with skipJoined, each device's first
// one when it started at 0 s (the monitor joined it running: its start is not the real one).
Operations operations(const std::string& jsonReport, bool skipJoined) {
  Operations out;
  const nlohmann::json report = nlohmann::json::parse(jsonReport);
  for (const auto& a : report.at("activities")) {
    if (a.at("end_s").is_null()) continue;
    auto& list = out[a.at("device").get<std::string>()];
    if (skipJoined && list.empty() && a.at("start_s").get<double>() == 0) continue;
    int error = a.at("error").get<int>();
    list.push_back(a.at("label").get<std::string>() + (error != 0 ? " error " + std::to_string(error) : ""));
  }
  return out;
}

// True if `part` occurs in `whole` as consecutive elements.
bool contiguous(const std::vector<std::string>& part, const std::vector<std::string>& whole) {
  for (size_t at = 0; at + part.size() <= whole.size(); ++at)
    if (std::equal(part.begin(), part.end(), whole.begin() + static_cast<std::ptrdiff_t>(at))) return true;
  return false;
}

TEST_F(Monitor, SeesTheServedPlantsOperationsInTheirOrder) {
  ServerProcess plant(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet", "--json", path("plant.json")}, kExample,
                      "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", kExample + "/cell.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms",
                         "--quiet", "--json", path("monitor.json")},
                        kExample, "ads: the PLC at ");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  ASSERT_TRUE(monitor.waitFor("monitor: cycle 3 completed")) << monitor.errorOutput();
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  EXPECT_NE(monitor.errorOutput().find("monitor: the model ran"), std::string::npos) << monitor.errorOutput();

  Operations watched = operations(readFile(path("monitor.json")), true);
  Operations served = operations(readFile(path("plant.json")), false);
  ASSERT_EQ(watched.size(), 2u) << readFile(path("monitor.json"));
  for (const auto& [device, ops] : watched) {
    EXPECT_GE(ops.size(), 2u) << device;  // two whole cycles at least: Press once, Clamp twice a cycle
    EXPECT_TRUE(contiguous(ops, served[device])) << device << ": the monitor's operations are not a stretch of the plant's";
  }
}

// One HTTP/1.0 GET on a fresh connection: the whole response, headers included.
std::string httpGet(int port, const std::string& target) {
  LoopbackClient c(port);
  const std::string request = "GET " + target + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
  if (!c.connected() || !c.send(std::vector<uint8_t>(request.begin(), request.end()))) return {};
  std::vector<uint8_t> response = c.receive(1 << 20);  // until the server closes
  return std::string(response.begin(), response.end());
}

TEST_F(Monitor, ServesTheHmiReadOnlyOverTheWatchedCell) {
  ServerProcess plant(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, kExample, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", kExample + "/cell.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--http",
                         "127.0.0.1:0", "--quiet"},
                        kExample, "hmi: serving http://");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  std::string model = httpGet(monitor.port(), "/api/model");
  EXPECT_NE(model.find("\"name\":\"Clamp\""), std::string::npos) << model;
  EXPECT_NE(model.find("\"readOnly\":true"), std::string::npos) << model;
  EXPECT_TRUE(monitor.waitFor("(read-only)")) << monitor.errorOutput();
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
}

TEST_F(Monitor, AWiredVariableThePlcLacksIsAnErrorAtStartUp) {
  ServerProcess plant(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, kExample, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  // bridge.yaml, the same cell against an external PLC, with one port wired to a name the PLC lacks.
  std::string cell = readFile(kExample + "/bridge.yaml");
  const std::string wiring = "    wiring: MAIN.Press\n";
  ASSERT_NE(cell.find(wiring), std::string::npos);
  cell.replace(cell.find(wiring), wiring.size(), "    wiring: { execute: MAIN.Press.execute, done: MAIN.Press.finished }\n");
  std::ofstream(path("cell.yaml")) << cell;
  std::string out;
  int status = shell(kExe + " monitor " + path("cell.yaml") + " --ads 127.0.0.1:" + std::to_string(plant.port()), out);
  EXPECT_EQ(status, 1) << out;
  EXPECT_NE(out.find("MAIN.Press.finished"), std::string::npos) << out;
  EXPECT_NE(out.find("cell.yaml:"), std::string::npos) << out;  // at its place in the cell file
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
}

TEST_F(Monitor, ACellWhoseSoftPlcIsNotTheServedOneIsAnErrorAtStartUp) {
  const std::string gearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell";
  ServerProcess plant(kExe, {"serve", gearbox + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, gearbox, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  std::string out;
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml --ads 127.0.0.1:" + std::to_string(plant.port()), out), 1) << out;
  EXPECT_NE(out.find("error[C032]: ads: the PLC has no variable 'MAIN.Clamp.execute' to wire to Clamp.execute"), std::string::npos)
      << out;
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
}

TEST_F(Monitor, ABadPollPeriodIsAUsageError) {
  std::string out;
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml --ads 127.0.0.1:1 --poll fast", out), 64) << out;
  EXPECT_NE(out.find("--poll: 'fast' is not a positive duration"), std::string::npos) << out;
}

}  // namespace
