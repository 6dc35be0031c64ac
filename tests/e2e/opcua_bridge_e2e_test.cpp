// End-to-end: the OPC UA client bridge. `virtcom exec plc/*.st --opcua ... --opcua-anonymous
// write` of examples/ads-cell in a second process is the PLC of opcua-bridge.yaml (`plc: opcua:`):
// the cell completes the same cycles as with the soft PLC in process; problems (a server not
// there, the default anonymous session that may not write, unknown nodes, browse paths leading
// nowhere) are reported at start with their position; nodes by browse path are resolved by both
// servers; a PLC lost mid-run ends the run as a fault, and a scenario's comm_loss
// cuts the link. The same cell against a PLC nobody here wrote: an npm node-opcua server
// (tests/e2e/opcua/bridge_plc_server.js) playing the example's MAIN.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::ServerProcess;
using virtcom::e2e::portClosedAfter;
using virtcom::e2e::shell;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kExample = std::string(VIRTCOM_SOURCE_DIR) + "/examples/ads-cell";
const std::string kNodeDir = VIRTCOM_OPCUA_CLIENT_DIR;

// "Cycle time    1.530 s (measured ..." of a summary table, in seconds; -1 if absent.
double cycleTime(const std::string& summary) {
  auto at = summary.find("Cycle time");
  return at == std::string::npos ? -1 : std::atof(summary.c_str() + at + 10);
}

class OpcuaBridgeE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("virtcom_opcua_bridge_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The example's program served over OPC UA in its own process.
  std::unique_ptr<ServerProcess> startPlc(std::vector<std::string> extra = {"--opcua-anonymous", "write"}) {
    std::vector<std::string> args{"exec", "plc/types.st", "plc/main.st", "--opcua", "127.0.0.1:0"};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<ServerProcess>(kExe, args, kExample, "opcua: serving opc.tcp://");
  }
  // bridge_plc_server.js: the example's MAIN in an npm node-opcua server, at ns=4 as on CODESYS.
  std::unique_ptr<ServerProcess> startNodeOpcuaPlc() {
    EXPECT_TRUE(std::filesystem::exists(kNodeDir + "/node_modules/node-opcua-server"))
        << "the npm node-opcua-server is missing: run `npm ci --prefix tests/e2e/opcua` (make test does)";
    return std::make_unique<ServerProcess>("/usr/bin/env", std::vector<std::string>{"node", "bridge_plc_server.js"}, kNodeDir,
                                           "node-opcua: serving opc.tcp://");
  }
  // opcua-bridge.yaml with the PLC's port, and `from` replaced by `to` (if given); its path.
  std::string bridgeCell(int port, const std::string& from = "", const std::string& to = "") {
    std::string text = readFile(kExample + "/opcua-bridge.yaml");
    const std::string url = "opc.tcp://127.0.0.1:4840\n";
    text.replace(text.find(url), url.size(), "opc.tcp://127.0.0.1:" + std::to_string(port) + "\n");
    if (!from.empty()) text.replace(text.find(from), from.size(), to);
    std::ofstream(dir_ / "opcua-bridge.yaml") << text;
    return (dir_ / "opcua-bridge.yaml").string();
  }
  // `virtcom run` of the cell against the PLC at `port` for 1000 cycles (longer than any test), started.
  std::unique_ptr<ServerProcess> startLongRun(int port) {
    return std::make_unique<ServerProcess>(kExe, std::vector<std::string>{"run", bridgeCell(port, "cycles: 2", "cycles: 1000"), "--quiet"},
                                           dir_.string(), "opcua: the OPC UA server at opc.tcp://");
  }
  int testScenario(const std::string& cell, const std::string& body, std::string& out) {
    std::ofstream(dir_ / "loss.yaml") << "name: loss\ncell: " << cell << "\n" << body;
    return shell(kExe + " test " + (dir_ / "loss.yaml").string() + " --jobs 1", out);
  }

  std::filesystem::path dir_;
};

TEST_F(OpcuaBridgeE2e, TheCellCompletesTheSameCyclesAsWithTheSoftPlcInProcess) {
  std::string inProcess;
  ASSERT_EQ(shell(kExe + " run " + kExample + "/cell.yaml", inProcess), 0) << inProcess;
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  std::string bridged;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port()), bridged), 0) << bridged;
  EXPECT_NE(bridged.find("opcua: the OPC UA server at opc.tcp://127.0.0.1:" + std::to_string(plc->port()) +
                         " is the controller (12 signals, subscribed, published every 10 ms)"),
            std::string::npos)
      << bridged;
  for (const std::string* out : {&inProcess, &bridged})
    EXPECT_NE(out->find("Run ended     completed: 2 cycle(s) completed"), std::string::npos) << *out;
  // The same cycle, give or take the polls each handshake waits for the other process.
  double softCycle = cycleTime(inProcess), bridgedCycle = cycleTime(bridged);
  EXPECT_GT(softCycle, 1.0) << inProcess;
  EXPECT_NEAR(bridgedCycle, softCycle, 0.25 * softCycle) << bridged;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
}

// Regression: node-opcua refused the UserAccessLevel the bridge read at start (its DataEncoding
// was an empty name, not a null one), so no device output was writable.
TEST_F(OpcuaBridgeE2e, TheCellCompletesItsCyclesAgainstANodeOpcuaServer) {
  auto plc = startNodeOpcuaPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  std::string out;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port()), out), 0) << out;
  // node-opcua publishes at most every 50 ms (its minimum publishing interval).
  EXPECT_NE(out.find("is the controller (12 signals, subscribed, published every 50 ms)"), std::string::npos) << out;
  EXPECT_NE(out.find("Run ended     completed: 2 cycle(s) completed"), std::string::npos) << out;
  // Both ways: the PLC's commands moved the devices, and their answers reached the PLC.
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
  EXPECT_NE(plc->errorOutput().find("node-opcua: 2 cycle(s)"), std::string::npos) << plc->errorOutput();
  for (const char* written : {"\"Clamp.done\":", "\"Press.done\":", "\"Press.actualForce\":"})
    EXPECT_NE(plc->errorOutput().find(written), std::string::npos) << written << plc->errorOutput();
}

// Basic256Sha256 on the bridge (`security:`, `pki:`) against `virtcom exec --opcua-security`
// with a read-write user: the server's certificate is not trusted at first (the run stops and
// says which file to move), then it is; SignAndEncrypt and Sign complete the cycles, the password
// encrypted with the server's key; a wrong password and a mode the server lacks are refused.
TEST_F(OpcuaBridgeE2e, SecuredChannelsWithTheTrustWorkflowAndAUser) {
  std::string out;
  const std::string users = (dir_ / "users.txt").string(), clientPki = (dir_ / "client-pki").string();
  ASSERT_EQ(shell("printf 'op-pass\\n' | " + kExe + " opcua-user add " + users + " operator --role read-write", out), 0) << out;
  auto plc = startPlc({"--opcua-users", users, "--opcua-security", "sign,sign-encrypt", "--opcua-pki", (dir_ / "server-pki").string(),
                       "--opcua-trust-any-client"});
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  // A timeout of 5 s: this build's RSA and the password hash on the server take longer than 500 ms.
  const auto secured = [&](const std::string& mode, const std::string& password) {
    const std::string cell = bridgeCell(plc->port(), "security: none", "security: " + mode + "\n    pki: " + clientPki +
                                                                           "\n    user: operator\n    password: " + password);
    std::string text = readFile(cell);
    text.replace(text.find("timeout: 500 ms"), 15, "timeout: 5 s");
    std::ofstream(cell) << text;
    return cell;
  };
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + secured("sign-encrypt", "op-pass"), out), 1) << out;
  EXPECT_NE(out.find("the server certificate is not trusted; to trust it, move " + clientPki + "/rejected/certs/"), std::string::npos)
      << out;
  std::vector<std::filesystem::path> rejected;
  for (const auto& entry : std::filesystem::directory_iterator(clientPki + "/rejected/certs")) rejected.push_back(entry.path());
  ASSERT_EQ(rejected.size(), 1u);
  std::filesystem::rename(rejected[0], clientPki + "/trusted/certs/" + rejected[0].filename().string());
  for (const char* mode : {"sign-encrypt", "sign"}) {
    out.clear();
    EXPECT_EQ(shell(kExe + " run " + secured(mode, "op-pass"), out), 0) << mode << out;
    EXPECT_NE(out.find("Run ended     completed: 2 cycle(s) completed"), std::string::npos) << mode << out;
  }
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + secured("sign", "wrong"), out), 1) << out;
  EXPECT_NE(out.find("BadUserAccessDenied"), std::string::npos) << out;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
  // A server without the mode asked for: the error names what it offers.
  plc = startPlc({"--opcua-anonymous", "write"});
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port(), "security: none", "security: sign\n    pki: " + clientPki), out), 1) << out;
  EXPECT_NE(out.find("has no endpoint with security"), std::string::npos) << out;
  EXPECT_NE(out.find("it offers"), std::string::npos) << out;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
}

TEST_F(OpcuaBridgeE2e, ANodeOpcuaServerKilledMidRunEndsTheRunAsAFault) {
  auto plc = startNodeOpcuaPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  auto run = startLongRun(plc->port());
  ASSERT_EQ(run->port(), plc->port()) << run->errorOutput();
  EXPECT_EQ(plc->signal(SIGKILL), 128 + SIGKILL);
  EXPECT_EQ(run->waitExit(), 2) << run->errorOutput();
  EXPECT_NE(run->errorOutput().find("opcua: link to the OPC UA server at opc.tcp://127.0.0.1:" + std::to_string(plc->port())),
            std::string::npos)
      << run->errorOutput();
}

TEST_F(OpcuaBridgeE2e, ProblemsAreReportedAtStartWithTheirPosition) {
  const int closedPort = portClosedAfter([this] { return startPlc(); });
  ASSERT_GT(closedPort, 0);
  std::string out;
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(closedPort), out), 1) << out;
  EXPECT_NE(out.find("opcua-bridge.yaml:12:15: error[C034]: opcua: cannot connect to the OPC UA server at opc.tcp://127.0.0.1:" +
                     std::to_string(closedPort) + ": Connection refused"),
            std::string::npos)
      << out;

  // The server's default: anonymous sessions read but may not write the devices' outputs.
  auto readOnly = startPlc({});
  ASSERT_GT(readOnly->port(), 0) << readOnly->errorOutput();
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(readOnly->port()), out), 1) << out;
  EXPECT_NE(out.find("opcua-bridge.yaml:28:13: error[C033]: opcua: 'MAIN.Clamp.done' (ns=4;s=|var|virtcom.Application.MAIN.Clamp.done) "
                     "is not writable for this session"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("--opcua-anonymous write"), std::string::npos) << out;
  EXPECT_EQ(readOnly->stop(), 0);

  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  out.clear();
  EXPECT_EQ(shell(kExe + " run " + bridgeCell(plc->port(), "    wiring: MAIN.Press\n", "    wiring: { execute: MAIN.Press.exec, done: MAIN.step }\n"),
                  out),
            1)
      << out;
  EXPECT_NE(out.find("error[C032]: opcua: the server has no node 'MAIN.Press.exec' (ns=4;s=|var|virtcom.Application.MAIN.Press.exec) "
                     "to wire to Press.execute"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("error[C033]: opcua: 'MAIN.step' (ns=4;s=|var|virtcom.Application.MAIN.step) is Int16 on the server but output "
                     "'Press.done' is BOOL"),
            std::string::npos)
      << out;
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
}

// Nodes by browse path, resolved by the server (TranslateBrowsePathsToNodeIds): MAIN and the
// FB instances are folders (node-opcua) or objects (virtcom) under Objects, their members
// components; a path leading nowhere is reported where it is written.
TEST_F(OpcuaBridgeE2e, NodesNamedByBrowsePathAreResolvedByBothServers) {
  const std::string prefix = "    node_prefix: \"ns=4;s=|var|virtcom.Application.\"\n";
  const std::string byPath = prefix + "    nodes:\n      MAIN.cycleDone: /4:MAIN/4:cycleDone\n      MAIN.Clamp.execute: /4:MAIN/4:Clamp/4:execute\n"
                                      "      MAIN.Clamp.done: /4:MAIN/4:Clamp.4:done\n";
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  auto nodeOpcua = startNodeOpcuaPlc();
  ASSERT_GT(nodeOpcua->port(), 0) << nodeOpcua->errorOutput();
  for (int port : {plc->port(), nodeOpcua->port()}) {
    std::string out;
    EXPECT_EQ(shell(kExe + " run " + bridgeCell(port, prefix, byPath), out), 0) << out;
    EXPECT_NE(out.find("is the controller (12 signals, subscribed"), std::string::npos) << out;
    EXPECT_NE(out.find("Run ended     completed: 2 cycle(s) completed"), std::string::npos) << out;

    out.clear();
    EXPECT_EQ(shell(kExe + " run " + bridgeCell(port, prefix, byPath + "      MAIN.Press.done: /4:MAIN/4:Press/4:finished\n"), out), 1) << out;
    EXPECT_NE(out.find("opcua-bridge.yaml:19:24: error[C032]: opcua: the browse path '/4:MAIN/4:Press/4:finished' of 'MAIN.Press.done' "
                       "leads to no node on the server: BadNoMatch (to wire to Press.done)"),
              std::string::npos)
        << out;
  }
  EXPECT_EQ(plc->stop(), 0) << plc->errorOutput();
  EXPECT_EQ(nodeOpcua->stop(), 0) << nodeOpcua->errorOutput();
}

TEST_F(OpcuaBridgeE2e, APlcLostMidRunEndsTheRunAsAFault) {
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  auto run = startLongRun(plc->port());
  ASSERT_EQ(run->port(), plc->port()) << run->errorOutput();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(plc->stop(), 0);
  EXPECT_EQ(run->waitExit(), 2) << run->errorOutput();
  EXPECT_NE(run->errorOutput().find("opcua: link to the OPC UA server at opc.tcp://127.0.0.1:"), std::string::npos) << run->errorOutput();
}

TEST_F(OpcuaBridgeE2e, AScenariosCommLossEndsTheRunAsAPlcFault) {
  auto plc = startPlc();
  ASSERT_GT(plc->port(), 0) << plc->errorOutput();
  const std::string body = "faults:\n  - {link: plc, comm_loss: [{at: 0.5 s, duration: 1 s}]}\nexpect:\n  - {run_end: plc_fault}\n";
  std::string out;
  EXPECT_EQ(testScenario(bridgeCell(plc->port()), body, out), 0) << out;
  EXPECT_NE(out.find("PASS  loss"), std::string::npos) << out;
  // Without the loss the run completes (against a PLC that starts afresh: the first run left
  // the other in the middle of its sequence).
  EXPECT_EQ(plc->stop(), 0);
  auto fresh = startPlc();
  ASSERT_GT(fresh->port(), 0) << fresh->errorOutput();
  out.clear();
  EXPECT_EQ(testScenario(bridgeCell(fresh->port()), "expect:\n  - {run_end: completed}\n", out), 0) << out;
  EXPECT_NE(out.find("PASS  loss"), std::string::npos) << out;
}

}  // namespace
