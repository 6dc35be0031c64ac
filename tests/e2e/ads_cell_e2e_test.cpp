// End-to-end: examples/ads-cell over ADS.
//  - `virtcom serve cell.yaml --ads`: the cell's soft PLC served to the real npm ads-client while
//    the cell runs (tests/e2e/ads/check_served_cell.js), also together with --modbus;
//  - the client bridge: `virtcom exec plc/*.st --ads` in a second process is the PLC of
//    bridge.yaml (`plc: ads:`), and the cell completes the same cycles as with the soft PLC in
//    process; connection, name and type problems are reported at start with their position;
//  - `virtcom test` on bridge.yaml: a scenario cuts the link (`{link: plc, comm_loss: ...}`), and
//    the run ends as a PLC fault (on_loss: fault) or holds the commands for the window (hold).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <chrono>
#include <thread>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/eventually.hpp"
#include "support/loopback_client.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::ServerProcess;
using virtcom::e2e::portClosedAfter;
using virtcom::e2e::shell;
using virtcom::test::eventually;
using virtcom::test::LoopbackClient;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kClientDir = VIRTCOM_ADS_CLIENT_DIR;
const std::string kExample = std::string(VIRTCOM_SOURCE_DIR) + "/examples/ads-cell";
const std::string kAnnounce = "ads: serving on ";

// The last value of each signal in a `--csv` file (time_s,signal,value).
std::map<std::string, std::string> finalValues(const std::filesystem::path& csv) {
  std::map<std::string, std::string> last;
  std::istringstream in(readFile(csv));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    size_t a = line.find(','), b = line.rfind(',');
    if (a != std::string::npos && b > a) last[line.substr(a + 1, b - a - 1)] = line.substr(b + 1);
  }
  return last;
}

// "Cycle time    1.530 s (measured ..." of a summary table, in seconds; -1 if absent.
double cycleTime(const std::string& summary) {
  auto at = summary.find("Cycle time");
  return at == std::string::npos ? -1 : std::atof(summary.c_str() + at + 10);
}

// One Modbus TCP request (unit 1) on a fresh connection; the response PDU, empty on failure.
std::vector<uint8_t> modbusRequest(int port, std::vector<uint8_t> pdu) {
  LoopbackClient c(port);
  std::vector<uint8_t> frame{0, 1, 0, 0, 0, static_cast<uint8_t>(pdu.size() + 1), 1};
  frame.insert(frame.end(), pdu.begin(), pdu.end());
  if (!c.connected() || !c.send(frame)) return {};
  std::vector<uint8_t> head = c.receive(7);  // MBAP header; bytes 4-5: the length from the unit id on
  if (head.size() < 7) return {};
  return c.receive(static_cast<size_t>(head[4] << 8 | head[5]) - 1);
}

TEST(ServeAds, TheServedCellsSoftPlcIsReadByTheNpmAdsClientWhileTheCellRuns) {
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/ads-client"))
      << "the npm ads-client is missing: run `npm ci --prefix tests/e2e/ads` (make test does)";
  ServerProcess cell(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, kExample, kAnnounce);
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  std::string out;
  EXPECT_EQ(shell("cd '" + kClientDir + "' && node check_served_cell.js " + std::to_string(cell.port()), out), 0) << out;
  EXPECT_NE(out.find("served cell checks passed"), std::string::npos) << out;
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
}

TEST(ServeAds, WithModbusTheCommandsOfTheSoftPlcAreReadOnly) {
  ServerProcess cell(kExe, {"serve", kExample + "/cell.yaml", "--ads", "127.0.0.1:0", "--modbus", "127.0.0.1:0", "--quiet"}, kExample,
                     "modbus: serving on ");
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  // The automatic map: coil 0 = Clamp.execute (the soft PLC's, so read-only), discrete 1 = Clamp.busy.
  bool executeSeen = false, busySeen = false;
  EXPECT_TRUE(eventually([&] {
    auto coils = modbusRequest(cell.port(), {0x01, 0, 0, 0, 1});
    auto inputs = modbusRequest(cell.port(), {0x02, 0, 1, 0, 1});
    executeSeen |= coils.size() == 3 && coils[2] == 1;
    busySeen |= inputs.size() == 3 && inputs[2] == 1;
    return executeSeen && busySeen;
  })) << cell.errorOutput();
  EXPECT_EQ(modbusRequest(cell.port(), {0x05, 0, 0, 0, 0}), (std::vector<uint8_t>{0x85, 0x02}));  // refused
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
  EXPECT_NE(cell.errorOutput().find(kAnnounce + "127.0.0.1:"), std::string::npos) << cell.errorOutput();  // ADS too
}

TEST(ServeAds, MistakesAreUsageErrors) {
  std::string out;
  // A cell made for an external PLC has no soft PLC to serve.
  EXPECT_EQ(shell(kExe + " serve " + std::string(VIRTCOM_SOURCE_DIR) + "/examples/modbus-cell/cell.yaml --ads 127.0.0.1:0", out), 64);
  EXPECT_NE(out.find("error: --ads serves the cell's soft PLC, but "), std::string::npos) << out;
  for (auto [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--ads-netid", "1.2.3"}, {"--ads-allow", "nobody"}, {"--ads", "127.0.0.1"}}) {
    out.clear();
    std::string args = option == "--ads" ? "--ads " + value : "--ads 127.0.0.1:0 " + option + " " + value;
    EXPECT_EQ(shell(kExe + " serve " + kExample + "/cell.yaml " + args, out), 64) << option;
    EXPECT_NE(out.find("error: " + option + ": "), std::string::npos) << out;
  }
}

// The client bridge: the cell against the soft PLC running plc/*.st in another process.
class AdsBridgeE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("virtcom_ads_bridge_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::unique_ptr<ServerProcess> startPlc() {
    return std::make_unique<ServerProcess>(kExe, std::vector<std::string>{"exec", "plc/types.st", "plc/main.st", "--ads", "127.0.0.1:0"},
                                           kExample, kAnnounce);
  }
  // bridge.yaml with the PLC's port, and `from` replaced by `to` (if given); its path.
  std::string bridgeCell(int port, const std::string& from = "", const std::string& to = "") {
    std::string text = readFile(kExample + "/bridge.yaml");
    text.replace(text.find("127.0.0.1:48898\n    netid"), 15, "127.0.0.1:" + std::to_string(port));
    if (!from.empty()) text.replace(text.find(from), from.size(), to);
    std::ofstream(dir_ / "bridge.yaml") << text;
    return (dir_ / "bridge.yaml").string();
  }

  std::filesystem::path dir_;
};

TEST_F(AdsBridgeE2e, TheCellCompletesTheSameCyclesAsWithTheSoftPlcInProcess) {
  std::string inProcess;
  ASSERT_EQ(shell(kExe + " run " + kExample + "/cell.yaml --csv " + (dir_ / "soft.csv").string(), inProcess), 0) << inProcess;
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  std::string bridged;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port()) + " --csv " + (dir_ / "ads.csv").string(), bridged), 0) << bridged;
  EXPECT_NE(bridged.find("ads: the PLC at 127.0.0.1:" + std::to_string(plc->port()) +
                         " (AmsNetId 127.0.0.1.1.1, port 851) is the controller (12 signals by handle, every step)"),
            std::string::npos)
      << bridged;
  for (const std::string* out : {&inProcess, &bridged})
    EXPECT_NE(out->find("Run ended     completed: 2 cycle(s) completed"), std::string::npos) << *out;
  auto soft = finalValues(dir_ / "soft.csv"), ads = finalValues(dir_ / "ads.csv");
  EXPECT_EQ(soft["MAIN.cycles"], "2");
  EXPECT_EQ(ads["MAIN.cycles"], "2");
  EXPECT_EQ(ads["MAIN.maxForce"], soft["MAIN.maxForce"]);
  EXPECT_EQ(ads["Press.actualForce"], soft["Press.actualForce"]);
  // The same cycle, give or take the ticks each handshake waits for the other process.
  double softCycle = cycleTime(inProcess), adsCycle = cycleTime(bridged);
  EXPECT_GT(softCycle, 1.0) << inProcess;
  EXPECT_NEAR(adsCycle, softCycle, 0.25 * softCycle) << bridged;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
}

TEST_F(AdsBridgeE2e, ProblemsAreReportedAtStartWithTheirPosition) {
  const int closedPort = portClosedAfter([this] { return startPlc(); });
  ASSERT_GT(closedPort, 0);
  std::string out;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(closedPort), out), 1) << out;
  EXPECT_NE(out.find("bridge.yaml:12:14: error[C034]: ads: cannot connect to the PLC at 127.0.0.1:" + std::to_string(closedPort) +
                     " (AmsNetId 127.0.0.1.1.1, port 851): Connection refused"),
            std::string::npos)
      << out;

  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  out.clear();
  std::string cell = bridgeCell(plc->port(), "    wiring: MAIN.Press\n",
                                "    wiring: { execute: MAIN.Press.exec, done: MAIN.step, programNumber: MAIN.Press }\n");
  EXPECT_EQ(shell(kExe + " run " + cell, out), 1) << out;
  EXPECT_NE(out.find("error[C032]: ads: the PLC has no variable 'MAIN.Press.exec' to wire to Press.execute"), std::string::npos) << out;
  EXPECT_NE(out.find("error[C033]: ads: 'MAIN.step' is INT on the PLC but output 'Press.done' is BOOL"), std::string::npos) << out;
  EXPECT_NE(out.find("error[C033]: ads: 'MAIN.Press' is a ST_PressIO on the PLC; only BOOL, numeric and enum variables can be wired"),
            std::string::npos)
      << out;
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port(), "wiring: MAIN.Clamp", "wiring: MAIN.Clmap"), out), 1) << out;
  EXPECT_NE(out.find("error[C030]: ads: no port of 'Clamp' matches a variable under 'MAIN.Clmap' on the PLC at"), std::string::npos)
      << out;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
}

// `netid:` in the cell file and `--ads-netid` read an AmsNetId with one parser, so they refuse the
// same text in the same words, each after its own key or option.
TEST_F(AdsBridgeE2e, TheCellFileAndTheOptionRefuseABadAmsNetIdInTheSameWords) {
  const std::string refusal = "'1.2.3' is not an AmsNetId (six numbers 0-255, e.g. 192.168.1.10.1.1)";
  std::string out;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(48898, "netid: 127.0.0.1.1.1", "netid: 1.2.3"), out), 1) << out;
  EXPECT_NE(out.find("bridge.yaml:13:12: error[C010]: 'netid': " + refusal), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell(kExe + " serve " + kExample + "/cell.yaml --ads 127.0.0.1:0 --ads-netid 1.2.3", out), 64) << out;
  EXPECT_NE(out.find("error: --ads-netid: " + refusal), std::string::npos) << out;
}

// The seed's setting: the gearbox cell against its PLC program over ADS, the signals named like
// the PLC's variables (`wiring: MAIN.Robot1` -> MAIN.Robot1.busy, ...), both sides at 10x speed.
TEST_F(AdsBridgeE2e, TheGearboxCellCommissionsAgainstItsProgramInAnotherProcess) {
  const std::string gearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell";
  std::string inProcess;
  ASSERT_EQ(shell(kExe + " run " + gearbox + "/cell.yaml --set MAIN.sequence=3", inProcess), 0) << inProcess;
  std::string text = readFile(gearbox + "/cell.yaml");
  const std::string sources =
      "  sources: [plc/types.st, plc/GVL.st, plc/handshake.st, plc/sequences.st, plc/jobs.st, plc/main.st]\n";
  ASSERT_NE(text.find(sources), std::string::npos);
  ServerProcess plc(kExe, {"exec", "plc/types.st", "plc/GVL.st", "plc/handshake.st", "plc/sequences.st", "plc/jobs.st", "plc/main.st", "--ads",
                           "127.0.0.1:0", "--set", "MAIN.sequence=3", "--speed", "10"},
                    gearbox, kAnnounce);
  ASSERT_GT(plc.port(), 0) << plc.errorOutput();
  text.replace(text.find(sources), sources.size(), "  ads: { address: 127.0.0.1:" + std::to_string(plc.port()) + " }\n");
  std::ofstream(dir_ / "gearbox.yaml") << text;
  std::string bridged;
  EXPECT_EQ(shell(kExe + " run " + (dir_ / "gearbox.yaml").string() + " --speed 10", bridged), 0) << bridged;
  EXPECT_NE(bridged.find("is the controller (28 signals by handle, every step)"), std::string::npos) << bridged;
  for (const std::string* out : {&inProcess, &bridged}) {
    EXPECT_NE(out->find("Run ended     completed: 1 cycle(s) completed"), std::string::npos) << *out;
    EXPECT_NE(out->find("Collisions    0\n"), std::string::npos) << *out;
  }
  EXPECT_NEAR(cycleTime(bridged), cycleTime(inProcess), 0.1 * cycleTime(inProcess)) << bridged;
  EXPECT_EQ(plc.stop(), 0) << plc.errorOutput();
}

TEST_F(AdsBridgeE2e, APlcLostMidRunEndsTheRunAsAFault) {
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  ServerProcess run(kExe, {"run", bridgeCell(plc->port(), "cycles: 2", "cycles: 1000"), "--quiet"}, dir_.string(), "ads: the PLC at ");
  ASSERT_EQ(run.port(), plc->port()) << run.errorOutput();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(plc->stop(), 0);
  EXPECT_EQ(run.waitExit(), 2) << run.errorOutput();
}

// `virtcom test` on bridge.yaml: a scenario cuts the link to the PLC in the other process
// (docs/scenarios.md, `{link: plc, comm_loss: ...}`); `expect` is the scenario's assertions.
class AdsLinkLossE2e : public AdsBridgeE2e {
 protected:
  int testScenario(const std::string& cell, const std::string& body, std::string& out) {
    std::ofstream(dir_ / "loss.yaml") << "name: loss\ncell: " << cell << "\n" << body;
    return shell(kExe + " test " + (dir_ / "loss.yaml").string() + " --jobs 1", out);
  }
};

TEST_F(AdsLinkLossE2e, OnLossFaultEndsTheRunAsAPlcFault) {
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  const std::string body = "faults:\n  - {link: plc, comm_loss: [{at: 0.5 s, duration: 1 s}]}\nexpect:\n  - {run_end: plc_fault}\n";
  std::string out;
  EXPECT_EQ(testScenario(bridgeCell(plc->port()), body, out), 0) << out;
  EXPECT_NE(out.find("PASS  loss"), std::string::npos) << out;
  // Without the loss the same assertion fails: the run completes.
  out.clear();
  EXPECT_EQ(testScenario(bridgeCell(plc->port()), "expect:\n  - {run_end: plc_fault}\n", out), 5) << out;
  EXPECT_NE(out.find("FAIL  loss"), std::string::npos) << out;
}

TEST_F(AdsLinkLossE2e, OnLossHoldStallsTheCycleForTheWindowThenGoesOn) {
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  const std::string cell = bridgeCell(plc->port(), "on_loss: fault", "on_loss: hold");
  const std::string expect = "expect:\n  - {run_end: completed}\n";
  // When the scenario's run ended ("completed at T s" of its PASS line), or -1.
  auto completedAt = [](const std::string& out) {
    const size_t at = out.find("completed at ");
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 13));
  };
  std::string held, plain;
  EXPECT_EQ(testScenario(cell, "faults:\n  - {link: plc, comm_loss: [{at: 0.3 s, duration: 2 s}]}\n" + expect, held), 0) << held;
  EXPECT_NE(held.find("PASS  loss"), std::string::npos) << held;
  EXPECT_EQ(testScenario(cell, expect, plain), 0) << plain;
  // Cut for 2 s, the cell waits (the devices keep their last commands) and the run completes
  // the same cycles about 2 s later.
  EXPECT_GT(completedAt(plain), 0.0) << plain;
  EXPECT_GE(completedAt(held), completedAt(plain) + 1.5) << held << plain;
}

TEST_F(AdsLinkLossE2e, ALinkFaultNeedsAnExternalPlc) {
  std::string out;
  EXPECT_EQ(testScenario(kExample + "/cell.yaml", "faults:\n  - {link: plc, comm_loss: [{at: 1 s, duration: 1 s}]}\n", out), 5) << out;
  EXPECT_NE(out.find("loss.yaml:4:6: error[C063]: the cell's controller is its soft PLC"), std::string::npos) << out;
}

}  // namespace
