// End-to-end: `virtcom monitor` watching a plant without a real one. `virtcom serve
// examples/ads-cell/cell.yaml --ads` in a second process plays the plant (its soft PLC and
// simulated devices, served over ADS, and with --modbus its device signals over Modbus TCP);
// the monitor reads the same cell's wiring (or Modbus map) from it and must see the served
// run's own operations: per device the same operations in the same order, with the same errors. Durations are not compared here (two processes paced by a shared,
// loaded machine); tests/unit/sim/operation_recogniser_test.cpp compares them exactly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>
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

// The monitor's completed operations, per device, are a stretch of the served plant's: the
// same operations in the same order (the monitor joins and leaves the plant mid-run).
void expectAStretchOfThePlants(const std::string& monitorJson, const std::string& plantJson, size_t atLeast) {
  Operations watched = operations(monitorJson, true);
  Operations served = operations(plantJson, false);
  ASSERT_EQ(watched.size(), 2u) << monitorJson;
  for (const auto& [device, ops] : watched) {
    EXPECT_GE(ops.size(), atLeast) << device;
    EXPECT_TRUE(contiguous(ops, served[device])) << device << ": the monitor's operations are not a stretch of the plant's";
  }
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
  // Two whole cycles at least: Press once, Clamp twice a cycle.
  expectAStretchOfThePlants(readFile(path("monitor.json")), readFile(path("plant.json")), 2);
}

// Over OPC UA the monitor reads the soft PLC's wired variables by their CODESYS-form node ids,
// as `serve --opcua` serves them, one Read a poll (a consistent image of a scan, as over ADS).
TEST_F(Monitor, SeesTheServedPlantsOperationsOverOpcua) {
  ServerProcess plant(kExe, {"serve", kExample + "/cell.yaml", "--opcua", "127.0.0.1:0", "--quiet", "--json", path("plant.json")}, kExample,
                      "opcua: serving opc.tcp://");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", kExample + "/cell.yaml", "--opcua", "opc.tcp://127.0.0.1:" + std::to_string(plant.port()), "--poll",
                         "5ms", "--quiet", "--json", path("monitor.json")},
                        kExample, "opcua: the OPC UA server at opc.tcp://");
  ASSERT_EQ(monitor.port(), plant.port()) << monitor.errorOutput();
  ASSERT_TRUE(monitor.waitFor("monitor: cycle 3 completed")) << monitor.errorOutput();
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  EXPECT_NE(monitor.errorOutput().find("is watched (read only)"), std::string::npos) << monitor.errorOutput();
  expectAStretchOfThePlants(readFile(path("monitor.json")), readFile(path("plant.json")), 2);
}

TEST_F(Monitor, AnOpcuaEndpointThatIsNotAUrlIsAUsageError) {
  std::string out;
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml --opcua 127.0.0.1:4840 --quiet", out), 64) << out;
  EXPECT_NE(out.find("--opcua: '127.0.0.1:4840' is not an opc.tcp URL (expected opc.tcp://HOST:PORT"), std::string::npos) << out;
}

// Over Modbus the monitor reads the cell's (automatic) Modbus map, as `serve --modbus` serves
// it; the soft PLC runs in the plant because --ads is served too. A Modbus PLC has no cycle
// marker, so the test watches a few of the plant's 1.3 s cycles instead of counting them. The
// tables are read with one request each, not as one image of a PLC cycle (docs/monitor.md), so
// on a loaded machine a handshake can be seen torn: the test asks for the plant's operations,
// not for their exact sequence.
TEST_F(Monitor, SeesTheServedPlantsOperationsOverModbus) {
  ServerProcess plant(kExe,
                      {"serve", kExample + "/cell.yaml", "--modbus", "127.0.0.1:0", "--ads", "127.0.0.1:0", "--quiet", "--json",
                       path("plant.json")},
                      kExample, "modbus: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", kExample + "/cell.yaml", "--modbus", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms",
                         "--quiet", "--json", path("monitor.json")},
                        kExample, "modbus: the PLC at ");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  EXPECT_TRUE(monitor.waitFor("is watched (read only)")) << monitor.errorOutput();
  std::this_thread::sleep_for(std::chrono::seconds(5));
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  Operations watched = operations(readFile(path("monitor.json")), true);
  Operations served = operations(readFile(path("plant.json")), false);
  ASSERT_EQ(watched.size(), 2u) << readFile(path("monitor.json"));
  for (const auto& [device, ops] : watched) {
    EXPECT_GE(ops.size(), 1u) << device;
    for (const std::string& op : ops)
      EXPECT_NE(std::find(served[device].begin(), served[device].end(), op), served[device].end())
          << device << ": " << op << " is not an operation of the plant";
  }
}

TEST_F(Monitor, AModbusPlcThatCannotBeReachedEndsTheMonitorAsALostLink) {
  std::string out;
  // Port 1 on the loopback: nothing listens there.
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml --modbus 127.0.0.1:1 --quiet", out), 2) << out;
  EXPECT_NE(out.find("modbus: link to the PLC at 127.0.0.1:1 lost: cannot connect"), std::string::npos) << out;
}

TEST_F(Monitor, NeedsExactlyOneLink) {
  std::string out;
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml", out), 64) << out;
  EXPECT_NE(out.find("one of --ads HOST:PORT, --opcua opc.tcp://HOST:PORT or --modbus HOST:PORT"), std::string::npos) << out;
  EXPECT_NE(shell(kExe + " monitor " + kExample + "/cell.yaml --ads 127.0.0.1:1 --modbus 127.0.0.1:1", out), 0) << out;
  EXPECT_NE(out.find("excludes"), std::string::npos) << out;
  EXPECT_EQ(shell(kExe + " monitor " + kExample + "/cell.yaml --opcua opc.tcp://127.0.0.1:1 --modbus 127.0.0.1:1", out), 64) << out;
  EXPECT_NE(out.find("one of --ads"), std::string::npos) << out;
}

// The text of examples/ads-cell/cell.yaml for a file elsewhere: its PLC sources by absolute path,
// each of `edits` (from, to) applied once, `extra` appended.
std::string cellCopy(const std::vector<std::pair<std::string, std::string>>& edits, const std::string& extra) {
  std::string cell = readFile(kExample + "/cell.yaml");
  std::vector<std::pair<std::string, std::string>> all = {
      {"sources: [plc/types.st, plc/main.st]", "sources: [" + kExample + "/plc/types.st, " + kExample + "/plc/main.st]"}};
  all.insert(all.end(), edits.begin(), edits.end());
  for (const auto& [from, to] : all) {
    const size_t at = cell.find(from);
    if (at == std::string::npos) return "edit not applicable: " + from;
    cell.replace(at, from.size(), to);
  }
  return cell + extra;
}

// The plant runs every operation twice as long as the model the monitor compares with: every
// completed operation is an alert, recorded as a fault. With a plan of one whole-day shift,
// every completed cycle is a part of it.
TEST_F(Monitor, RecordsTheWatchedPlantAlertsAndProductionInTheHistorian) {
  const std::string slowed = cellCopy({{"duration: 0.3 s", "duration: 0.6 s"},
                                       {"duration: 0.2 s", "duration: 0.4 s"},
                                       {"approach_time: 0.2 s, press_time: 0.3 s, return_time: 0.2 s", "approach_time: 0.4 s, press_time: 0.6 s, return_time: 0.4 s"}},
                                      "");
  ASSERT_EQ(slowed.find("edit not applicable"), std::string::npos) << slowed;
  std::ofstream(path("slowed.yaml")) << slowed;
  std::ofstream(path("planned.yaml")) << cellCopy({}, "plan:\n  shifts:\n    - { name: AllDay, start: \"00:00\", end: \"24:00\", parts: 1000 }\n");
  ServerProcess plant(kExe, {"serve", path("slowed.yaml"), "--ads", "127.0.0.1:0", "--quiet"}, kExample, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", path("planned.yaml"), "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms", "--quiet",
                         "--json", path("monitor.json"), "--history", path("h.sqlite")},
                        kExample, "ads: the PLC at ");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  ASSERT_TRUE(monitor.waitFor("monitor: cycle 2 completed")) << monitor.errorOutput();
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  EXPECT_NE(monitor.errorOutput().find("monitor: alert at"), std::string::npos) << monitor.errorOutput();
  EXPECT_NE(monitor.errorOutput().find("history: run 1 recorded in " + path("h.sqlite")), std::string::npos) << monitor.errorOutput();

  // The JSON report: the whole-day shift's parts are the cycles completed; a station per device.
  const nlohmann::json watched = nlohmann::json::parse(readFile(path("monitor.json")));
  const auto& production = watched.at("production");
  uint32_t parts = 0;
  for (const auto& shift : production.at("shifts")) {
    EXPECT_EQ(shift.at("shift"), "AllDay");
    EXPECT_EQ(shift.at("plan"), 1000);
    EXPECT_GT(shift.at("plan_now").get<double>(), 0);
    parts += shift.at("actual").get<uint32_t>();
  }
  const uint32_t cycles = watched.at("run").at("cycles_completed").get<uint32_t>();
  EXPECT_GE(cycles, 2u);
  EXPECT_EQ(parts, cycles);
  ASSERT_EQ(production.at("stations").size(), 2u);
  EXPECT_EQ(production.at("stations")[0].at("device"), "Clamp");
  EXPECT_FALSE(watched.at("faults").empty());

  // The historian: the run, its activities and alerts as the JSON had them, and the shift.
  std::string out;
  ASSERT_EQ(shell(kExe + " history " + path("h.sqlite") + " --run 1", out), 0) << out;
  EXPECT_NE(out.find("interrupted"), std::string::npos) << out;
  EXPECT_NE(out.find("AllDay"), std::string::npos) << out;
  ASSERT_EQ(shell(kExe + " history " + path("h.sqlite") + " --json " + path("history.json"), out), 0) << out;
  const nlohmann::json recorded = nlohmann::json::parse(readFile(path("history.json")));
  EXPECT_EQ(recorded.at("activities").size(), watched.at("activities").size());
  EXPECT_EQ(recorded.at("faults"), watched.at("faults"));
  EXPECT_EQ(recorded.at("run").at("cycles_completed"), cycles);
}

// One HTTP/1.0 GET on a fresh connection: the whole response, headers included.
std::string httpGet(int port, const std::string& target) {
  LoopbackClient c(port);
  const std::string request = "GET " + target + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
  if (!c.connected() || !c.send(std::vector<uint8_t>(request.begin(), request.end()))) return {};
  std::vector<uint8_t> response = c.receive(1 << 20);  // until the server closes
  return std::string(response.begin(), response.end());
}

// One HTTP/1.0 POST of a JSON body on a fresh connection: the whole response.
std::string httpPost(int port, const std::string& target, const std::string& body) {
  LoopbackClient c(port);
  const std::string request = "POST " + target + " HTTP/1.0\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
                              std::to_string(body.size()) + "\r\n\r\n" + body;
  if (!c.connected() || !c.send(std::vector<uint8_t>(request.begin(), request.end()))) return {};
  std::vector<uint8_t> response = c.receive(1 << 20);
  return std::string(response.begin(), response.end());
}

// The port a process announced after `prefix` on a line ending in `lineEnd` ("hmi: serving
// http://127.0.0.1:PORT/ (loopback, writes allowed)"), 0 if none.
int announcedPort(ServerProcess& p, const std::string& prefix, const std::string& lineEnd) {
  if (!p.waitFor(prefix) || !p.waitFor(lineEnd)) return 0;
  const std::string& err = p.errorOutput();
  const size_t colon = err.find(':', err.find(prefix) + prefix.size());
  return colon == std::string::npos ? 0 : std::atoi(err.c_str() + colon + 1);
}

// Over Modbus the PLC's cycle marker is read where the cell's `modbus: cycle_done:` puts it
// (served there by `serve --modbus` from the soft PLC it runs with --ads): the monitor counts
// the plant's cycles. The plant starts paused (its HMI) until the monitor watches, and is paused
// again before either stops, so both count the same cycles.
TEST_F(Monitor, CountsThePlantsCyclesOverModbusWhereTheMapPutsCycleDone) {
  std::ofstream(path("marked.yaml")) << cellCopy({}, "modbus:\n  cycle_done: { table: discrete, address: 100 }\n");
  ServerProcess plant(kExe,
                      {"serve", path("marked.yaml"), "--modbus", "127.0.0.1:0", "--ads", "127.0.0.1:0", "--http", "127.0.0.1:0",
                       "--hmi-paused", "--quiet", "--json", path("plant.json")},
                      kExample, "modbus: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  const int hmi = announcedPort(plant, "hmi: serving http://", "writes allowed)");
  ASSERT_GT(hmi, 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", path("marked.yaml"), "--modbus", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms",
                         "--quiet", "--json", path("monitor.json")},
                        kExample, "modbus: the PLC at ");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  ASSERT_TRUE(monitor.waitFor("is watched (read only)")) << monitor.errorOutput();
  ASSERT_NE(httpPost(hmi, "/api/control", R"({"action": "run"})").find(" 200 "), std::string::npos);
  ASSERT_TRUE(monitor.waitFor("monitor: cycle 2 completed")) << monitor.errorOutput();
  ASSERT_NE(httpPost(hmi, "/api/control", R"({"action": "pause"})").find(" 200 "), std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the monitor's polls catch up with the paused plant
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  const nlohmann::json watched = nlohmann::json::parse(readFile(path("monitor.json")));
  const nlohmann::json served = nlohmann::json::parse(readFile(path("plant.json")));
  EXPECT_GE(watched.at("run").at("cycles_completed").get<uint32_t>(), 2u);
  EXPECT_EQ(watched.at("run").at("cycles_completed"), served.at("run").at("cycles_completed"))
      << "the monitor counted the served run's cycles";
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

// Production rows are written while the monitor runs (the current shift's row each time a part
// completes and every second), so a monitor killed with SIGKILL, which writes nothing when it
// stops, still leaves them in the historian, up to its last commit.
TEST_F(Monitor, AKilledMonitorKeepsItsProductionRowsInTheHistorian) {
  std::ofstream(path("planned.yaml")) << cellCopy({}, "plan:\n  shifts:\n    - { name: AllDay, start: \"00:00\", end: \"24:00\", parts: 1000 }\n");
  ServerProcess plant(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, kExample, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", path("planned.yaml"), "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms", "--quiet",
                         "--history", path("h.sqlite")},
                        kExample, "ads: the PLC at ");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  ASSERT_TRUE(monitor.waitFor("monitor: cycle 2 completed")) << monitor.errorOutput();
  std::this_thread::sleep_for(std::chrono::seconds(1));  // past the writer's next commit (at most 200 ms)
  EXPECT_EQ(monitor.signal(SIGKILL), 128 + SIGKILL) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  EXPECT_EQ(monitor.errorOutput().find("history: run 1 recorded"), std::string::npos) << "killed: it never got to end the run";

  std::string out;
  ASSERT_EQ(shell(kExe + " history " + path("h.sqlite") + " --run 1", out), 0) << out;
  EXPECT_NE(out.find("not ended"), std::string::npos) << out;
  std::smatch row;
  ASSERT_TRUE(std::regex_search(out, row, std::regex(R"((\d{4}-\d\d-\d\d) +AllDay +1000 +[0-9.]+ +(\d+))"))) << out;
  EXPECT_GE(std::stoi(row[2].str()), 2) << "the two cycles completed before the kill: " << out;
}

// The position of the real PLC's state machine: the gearbox's SFC variant served as the plant,
// the monitor finds every step of the cell's program in the PLC by name; its HMI lists them and
// streams the active ones, and the historian records the step flags as signals.
TEST_F(Monitor, FollowsThePlcsSfcStepsInTheHmiAndTheHistorian) {
  const std::string gearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell";
  ServerProcess plant(kExe, {"serve", gearbox + "/cell-sfc.yaml", "--ads", "127.0.0.1:0", "--quiet"}, gearbox, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", gearbox + "/cell-sfc.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms",
                         "--http", "127.0.0.1:0", "--history", path("h.sqlite"), "--quiet"},
                        gearbox, "hmi: serving http://");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  std::smatch found;
  const std::string err = monitor.errorOutput();
  ASSERT_TRUE(std::regex_search(err, found, std::regex("the PLC has (\\d+) of the (\\d+) SFC steps"))) << err;
  EXPECT_GT(std::stoi(found[2]), 5);
  EXPECT_EQ(found[1], found[2]) << "every step of the served program is found in the PLC";

  const std::string model = httpGet(monitor.port(), "/api/model");
  EXPECT_NE(model.find(R"("sfcSteps":["MAIN.Load",)"), std::string::npos) << model;
  // The stream's first frame carries the active steps, [index, ms in the step] each: at least
  // one step is active in a running chart (the plant runs in real time: the first cycle lasts
  // about 100 s, longer than this test).
  LoopbackClient viewer(monitor.port());
  const std::string request = "GET /api/stream HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
  ASSERT_TRUE(viewer.send(std::vector<uint8_t>(request.begin(), request.end())));
  const std::vector<uint8_t> frames = viewer.receive(1 << 16);  // what came within the 5 s receive timeout
  const std::string text(frames.begin(), frames.end());
  EXPECT_TRUE(std::regex_search(text, std::regex(R"re("steps":\[\[\d+,\d+\])re"))) << text.substr(0, 2000);
  viewer.close();
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();

  std::string out;
  ASSERT_EQ(shell(kExe + " history " + path("h.sqlite") + " --csv " + path("h.csv"), out), 0) << out;
  const std::string csv = readFile(path("h.csv"));
  EXPECT_NE(csv.find("MAIN.Load.X"), std::string::npos) << csv.substr(0, 2000);
  EXPECT_NE(csv.find("MAIN.Robot1Wait.X"), std::string::npos) << csv.substr(0, 2000);
}
