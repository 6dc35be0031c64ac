// End-to-end: a cell served over Modbus TCP (`virtcom serve examples/modbus-cell/cell.yaml`)
// driven by libmodbus and mbpoll as the external PLC would, and the client bridge
// (examples/modbus-cell/bridge.yaml) commissioning the cell against virtcom's own soft PLC
// (`virtcom exec controller.st --modbus`) in another process, and `virtcom test` cutting that
// link in a scenario (on_loss fault and hold).
#include <modbus.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "modbus_client.hpp"
#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/eventually.hpp"
#include "support/loopback_client.hpp"
#include "support/read_file.hpp"

namespace {

using virtcom::e2e::connectModbus;
using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::eventually;
using virtcom::test::LoopbackClient;
using virtcom::test::readFile;
const std::string kAnnounce = "modbus: serving on ";

const char* const kExe = VIRTCOM_EXE;
const std::string kExample = std::string(VIRTCOM_SOURCE_DIR) + "/examples/modbus-cell";

// examples/modbus-cell/cell.yaml's map.
constexpr int kClampExecuteCoil = 0, kPressExecuteCoil = 1;
constexpr int kClampProgramHolding = 0, kPressProgramHolding = 1;
constexpr int kClampDoneInput = 0, kClampBusyInput = 1, kPressDoneInput = 2;
constexpr int kPressForceInputReg = 2, kPressPositionInputReg = 4;
constexpr int kPressDoneHolding = 10, kPressForceHolding = 11;

class ServeE2e : public ::testing::Test {
 protected:
  virtual std::vector<std::string> serveArgs() const { return {"serve", kExample + "/cell.yaml", "--modbus", "127.0.0.1:0", "--quiet"}; }
  void SetUp() override {
    cell_ = std::make_unique<ServerProcess>(kExe, serveArgs(), kExample, kAnnounce);
    port_ = cell_->port();
    ASSERT_GT(port_, 0) << "no 'modbus: serving on' line; stderr so far:\n" << cell_->errorOutput();
  }
  void TearDown() override {
    for (modbus_t* ctx : contexts_) {
      modbus_close(ctx);
      modbus_free(ctx);
    }
    if (port_ > 0) {
      EXPECT_EQ(cell_->stop(), 0) << cell_->errorOutput();
    }
  }
  modbus_t* connect() {
    modbus_t* ctx = connectModbus(port_);
    if (ctx) contexts_.push_back(ctx);
    return ctx;
  }
  bool discrete(modbus_t* ctx, int address) {
    uint8_t bit = 0;
    return modbus_read_input_bits(ctx, address, 1, &bit) == 1 && bit;
  }

  std::unique_ptr<ServerProcess> cell_;
  int port_ = 0;
  std::vector<modbus_t*> contexts_;
};

TEST_F(ServeE2e, ThePlcCommandsTheDevicesAndReadsTheirStatus) {
  modbus_t* plc = connect();
  ASSERT_NE(plc, nullptr) << modbus_strerror(errno);
  // The clamp handshake: program, execute, done (held until execute drops).
  ASSERT_EQ(modbus_write_register(plc, kClampProgramHolding, 1), 1) << modbus_strerror(errno);
  ASSERT_EQ(modbus_write_bit(plc, kClampExecuteCoil, 1), 1);
  EXPECT_TRUE(eventually([&] { return discrete(plc, kClampBusyInput); }));
  EXPECT_TRUE(eventually([&] { return discrete(plc, kClampDoneInput); }));
  ASSERT_EQ(modbus_write_bit(plc, kClampExecuteCoil, 0), 1);
  EXPECT_TRUE(eventually([&] { return !discrete(plc, kClampDoneInput); }));
  // The press (needs the locked clamp): force as REAL, position as INT in 0.1 mm, the same
  // status again in holding registers.
  ASSERT_EQ(modbus_write_register(plc, kPressProgramHolding, 1), 1);
  ASSERT_EQ(modbus_write_bit(plc, kPressExecuteCoil, 1), 1);
  EXPECT_TRUE(eventually([&] {
    uint16_t r[2];
    return modbus_read_input_registers(plc, kPressForceInputReg, 2, r) == 2 && modbus_get_float_abcd(r) > 100.0f;
  }));
  EXPECT_TRUE(eventually([&] {
    uint16_t r[2];  // DINT, low word first
    return modbus_read_registers(plc, kPressForceHolding, 2, r) == 2 && static_cast<int32_t>(r[0] | (uint32_t(r[1]) << 16)) > 100;
  }));
  EXPECT_TRUE(eventually([&] {
    uint16_t r = 0;
    return modbus_read_input_registers(plc, kPressPositionInputReg, 1, &r) == 1 && r == 1200;  // stroke 120 mm
  }));
  EXPECT_TRUE(eventually([&] { return discrete(plc, kPressDoneInput); }));
  uint16_t done = 0;
  ASSERT_EQ(modbus_read_registers(plc, kPressDoneHolding, 1, &done), 1);
  EXPECT_EQ(done, 1);
  // Status is read-only, the tables end where the map ends.
  EXPECT_EQ(modbus_write_register(plc, kPressDoneHolding, 0), -1);
  EXPECT_EQ(errno, EMBXILADD);
  uint16_t regs[8];
  EXPECT_EQ(modbus_read_input_registers(plc, 0, 6, regs), -1);
  EXPECT_EQ(errno, EMBXILADD);
}

TEST_F(ServeE2e, MbpollReadsAndWritesEveryTable) {
  if (::access("/usr/bin/mbpoll", X_OK) != 0) {
    if (const char* require = std::getenv("VIRTCOM_REQUIRE_MBPOLL"); require && std::string(require) == "1")
      FAIL() << "mbpoll is not installed (apt-get install mbpoll) and VIRTCOM_REQUIRE_MBPOLL=1";
    GTEST_SKIP() << "mbpoll is not installed";
  }
  const std::string mbpoll = "/usr/bin/mbpoll -m tcp -a 1 -0 -1 -o 5 -p " + std::to_string(port_);
  std::string out;
  ASSERT_EQ(shell(mbpoll + " -t 4 -r 0 127.0.0.1 1", out), 0) << out;  // Clamp.programNumber
  ASSERT_EQ(shell(mbpoll + " -t 0 -r 0 127.0.0.1 1", out), 0) << out;  // Clamp.execute
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr);
  ASSERT_TRUE(eventually([&] { return discrete(ctx, kClampDoneInput); }));
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 1 -r 0 -c 4 127.0.0.1", out), 0) << out;  // discrete inputs
  EXPECT_NE(out.find("[0]: \t1"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 0 -r 0 -c 2 127.0.0.1", out), 0) << out;  // coils read back
  EXPECT_NE(out.find("[0]: \t1"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 4 -r 0 -c 2 127.0.0.1", out), 0) << out;  // holding registers
  EXPECT_NE(out.find("[0]: \t1"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 3 -r 0 -c 5 127.0.0.1", out), 0) << out;  // input registers
  EXPECT_NE(out.find("[0]: \t0"), std::string::npos) << out;             // Clamp.error
  out.clear();
  EXPECT_NE(shell(mbpoll + " -t 4 -r 10 127.0.0.1 5", out), 0) << out;  // read-only status
  EXPECT_NE(out.find("Illegal data address"), std::string::npos) << out;
}

TEST_F(ServeE2e, ManyClientsAndAbruptDisconnectsDoNotStopTheCell) {
  std::vector<modbus_t*> clients;
  for (int i = 0; i < 8; ++i) {
    clients.push_back(connect());
    ASSERT_NE(clients.back(), nullptr);
  }
  for (const std::vector<uint8_t>& bytes : {std::vector<uint8_t>{0, 1, 0, 0, 0, 6, 1, 3},
                                            std::vector<uint8_t>{'G', 'E', 'T', ' ', '/', '\r', '\n'}}) {
    LoopbackClient c(port_);
    ASSERT_TRUE(c.connected());
    ASSERT_TRUE(c.send(bytes));
    c.reset();
  }
  std::vector<std::thread> threads;
  std::vector<int> ok(clients.size(), 0);
  for (size_t i = 0; i < clients.size(); ++i)
    threads.emplace_back([&, i] {
      uint8_t bits[4];
      uint16_t regs[5];
      for (int k = 0; k < 40; ++k) {
        ok[i] += modbus_read_input_bits(clients[i], 0, 4, bits) == 4;
        ok[i] += modbus_read_input_registers(clients[i], 0, 5, regs) == 5;
        ok[i] += modbus_write_register(clients[i], kPressProgramHolding, static_cast<uint16_t>(i)) == 1;
      }
    });
  for (auto& t : threads) t.join();
  for (size_t i = 0; i < clients.size(); ++i) EXPECT_EQ(ok[i], 120) << "client " << i;
  modbus_t* late = connect();  // still served after all that, and the cell still runs
  ASSERT_NE(late, nullptr);
  ASSERT_EQ(modbus_write_register(late, kClampProgramHolding, 1), 1);
  ASSERT_EQ(modbus_write_bit(late, kClampExecuteCoil, 1), 1);
  EXPECT_TRUE(eventually([&] { return discrete(late, kClampDoneInput); }));
}

// serve --modbus --audit-writes each: the external PLC's writes into the cell's signals are
// audited like writes into the soft PLC, naming the signal, its table and address, and its value.
class ServeAuditE2e : public ServeE2e {
 protected:
  std::vector<std::string> serveArgs() const override {
    auto args = ServeE2e::serveArgs();
    args.insert(args.end(), {"--audit-writes", "each"});
    return args;
  }
};

TEST_F(ServeAuditE2e, ThePlcsWritesAreLoggedAsTheSignalsTheyChange) {
  modbus_t* plc = connect();
  ASSERT_NE(plc, nullptr) << modbus_strerror(errno);
  ASSERT_EQ(modbus_write_register(plc, kPressProgramHolding, 3), 1) << modbus_strerror(errno);
  EXPECT_TRUE(cell_->waitFor(" Press.programNumber (holding 1): 0 -> 3\n")) << cell_->errorOutput();
  ASSERT_EQ(modbus_write_bit(plc, kClampExecuteCoil, 1), 1) << modbus_strerror(errno);
  EXPECT_TRUE(cell_->waitFor(" Clamp.execute (coil 0): FALSE -> TRUE\n")) << cell_->errorOutput();
  EXPECT_NE(cell_->errorOutput().find("modbus 127.0.0.1:"), std::string::npos) << cell_->errorOutput();
  EXPECT_EQ(cell_->stop(), 0) << cell_->errorOutput();
  port_ = 0;
  EXPECT_NE(cell_->errorOutput().find("audit: 2 external writes (ads 0, modbus 2, opcua 0, http 0)"), std::string::npos)
      << cell_->errorOutput();
}

TEST(ServeCli, NothingToServeIsAUsageError) {
  std::string out;
  EXPECT_EQ(shell(std::string(kExe) + " serve " + kExample + "/cell.yaml", out), 64) << out;
  EXPECT_NE(out.find("error: nothing to serve: give --modbus HOST:PORT"), std::string::npos) << out;
  out.clear();  // `run` needs a controller, which a cell made for serving does not have
  EXPECT_EQ(shell(std::string(kExe) + " run " + kExample + "/cell.yaml", out), 64) << out;
  EXPECT_NE(out.find("the cell has no controller"), std::string::npos) << out;
}

TEST(ModbusMapCli, MarkdownTableOfTheExampleMatchesItsGoldenFile) {
  auto file = std::filesystem::path(::testing::TempDir()) / ("virtcom_map_" + std::to_string(::getpid()) + ".md");
  std::string out;
  ASSERT_EQ(shell(std::string(kExe) + " modbus-map " + kExample + "/cell.yaml --format markdown -o " + file.string(), out), 0) << out;
  EXPECT_EQ(readFile(file), readFile(std::string(VIRTCOM_SOURCE_DIR) + "/tests/e2e/data/modbus_cell_map.md"));
  std::filesystem::remove(file);
  out.clear();
  ASSERT_EQ(shell(std::string(kExe) + " modbus-map " + kExample + "/bridge.yaml --bridge", out), 0) << out;
  EXPECT_NE(out.find("holding,2052,REAL,Press.actualForce,status,read/write,high_first,1\n"), std::string::npos) << out;
}

// The bridge: the cell polls the soft PLC running controller.st in another process.
class BridgeE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("virtcom_bridge_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // bridge.yaml with the PLC's address replaced and `extra` applied; its path.
  std::string bridgeCell(int port, const std::string& onLoss = "fault") {
    std::string text = readFile(kExample + "/bridge.yaml");
    text.replace(text.find("127.0.0.1:1502\n    unit"), 14, "127.0.0.1:" + std::to_string(port));
    text.replace(text.find("on_loss: fault"), 14, "on_loss: " + onLoss);
    std::ofstream(dir_ / "bridge.yaml") << text;
    return (dir_ / "bridge.yaml").string();
  }

  std::filesystem::path dir_;
};

TEST_F(BridgeE2e, TheCellCommissionsAgainstTheSoftPlcInAnotherProcess) {
  ServerProcess plc(kExe, {"exec", "plc/controller.st", "--modbus", "127.0.0.1:0"}, kExample, kAnnounce);
  ASSERT_GT(plc.port(), 0) << plc.errorOutput();
  std::string out;
  // The time limit ends the run (exit 3): an external controller has no cycle marker.
  EXPECT_EQ(shell(std::string(kExe) + " run " + bridgeCell(plc.port()) + " --time-limit 3s", out), 3) << out;
  EXPECT_NE(out.find("is the controller (polled every 10 ms)"), std::string::npos) << out;
  EXPECT_NE(out.find("Press   press"), std::string::npos) << out;
  modbus_t* ctx = connectModbus(plc.port());
  ASSERT_NE(ctx, nullptr);
  uint16_t cycles = 0, force[2] = {};
  EXPECT_EQ(modbus_read_registers(ctx, 1044, 1, &cycles), 1);  // %MW20
  EXPECT_EQ(modbus_read_registers(ctx, 2054, 2, force), 2);    // %MD3, high word first
  EXPECT_GE(cycles, 1) << "not one clamp-press-unclamp cycle in 3 s";
  EXPECT_GT(modbus_get_float_abcd(force), 1000.0f);  // the press force reached the PLC
  modbus_close(ctx);
  modbus_free(ctx);
  EXPECT_EQ(plc.stop(), 0) << plc.errorOutput();
}

// `cycle_done:` places the external PLC's cycle marker (controller.st's coil 2): the run counts
// the PLC's cycles there and ends after `run: cycles` of them (exit 0), as a soft PLC's run does.
TEST_F(BridgeE2e, ThePlcsCycleMarkerEndsTheRunAfterItsCycles) {
  ServerProcess plc(kExe, {"exec", "plc/controller.st", "--modbus", "127.0.0.1:0"}, kExample, kAnnounce);
  ASSERT_GT(plc.port(), 0) << plc.errorOutput();
  std::string cell = readFile(bridgeCell(plc.port()));
  cell.replace(cell.find("# cycle_done:"), 13, "cycle_done:");
  std::ofstream(dir_ / "cycles.yaml") << cell << "run:\n  cycles: 2\n";
  std::string out;
  EXPECT_EQ(shell(std::string(kExe) + " run " + (dir_ / "cycles.yaml").string() + " --time-limit 20s --json " + (dir_ / "r.json").string(), out), 0) << out;
  const std::string json = readFile((dir_ / "r.json").string());
  EXPECT_TRUE(std::regex_search(json, std::regex(R"re("cycles_completed": ?2\b)re"))) << json.substr(0, 1500);
  modbus_t* ctx = connectModbus(plc.port());
  ASSERT_NE(ctx, nullptr);
  uint16_t cycles = 0;
  EXPECT_EQ(modbus_read_registers(ctx, 1044, 1, &cycles), 1);  // %MW20: the PLC's own count
  EXPECT_GE(cycles, 2);
  modbus_close(ctx);
  modbus_free(ctx);
  EXPECT_EQ(plc.stop(), 0) << plc.errorOutput();
}

TEST_F(BridgeE2e, ALostPlcIsAFaultOrHeldAsConfigured) {
  int closedPort = 0;
  {  // a port that was free a moment ago: nothing listens there any more
    ServerProcess plc(kExe, {"exec", "plc/controller.st", "--modbus", "127.0.0.1:0"}, kExample, kAnnounce);
    closedPort = plc.port();
    ASSERT_GT(closedPort, 0) << plc.errorOutput();
    EXPECT_EQ(plc.stop(), 0);
  }
  std::string out;
  EXPECT_EQ(shell(std::string(kExe) + " run " + bridgeCell(closedPort) + " --time-limit 1s", out), 2) << out;
  EXPECT_NE(out.find("lost: cannot connect"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(shell(std::string(kExe) + " run " + bridgeCell(closedPort, "hold") + " --time-limit 0.3s --quiet", out), 3) << out;
  EXPECT_NE(out.find("(holding the last commands, retrying every poll)"), std::string::npos) << out;
}

// `virtcom test` on bridge.yaml: a scenario cuts the Modbus link to the PLC in the other process
// (docs/scenarios.md, `{link: plc, comm_loss: ...}`), as ads_cell_e2e_test.cpp does over ADS.
// The cell counts the PLC's cycles at its marker, so a run without the cut completes 2 cycles.
// Each scenario gets a PLC of its own, started afresh: one left mid-cycle by the run before
// would command the press at once.
class ModbusLinkLossE2e : public BridgeE2e {
 protected:
  // The scenario `body` on bridge.yaml (on_loss as given, 2 cycles counted at the marker).
  int testScenario(const std::string& onLoss, const std::string& body, std::string& out) {
    ServerProcess plc(kExe, {"exec", "plc/controller.st", "--modbus", "127.0.0.1:0"}, kExample, kAnnounce);
    EXPECT_GT(plc.port(), 0) << plc.errorOutput();
    std::string cell = readFile(bridgeCell(plc.port(), onLoss));
    cell.replace(cell.find("# cycle_done:"), 13, "cycle_done:");
    std::ofstream(dir_ / "cycles.yaml") << cell << "run:\n  cycles: 2\n";
    std::ofstream(dir_ / "loss.yaml") << "name: loss\ncell: cycles.yaml\ntime_limit: 20 s\n" << body;
    const int status = shell(std::string(kExe) + " test " + (dir_ / "loss.yaml").string() + " --jobs 1", out);
    EXPECT_EQ(plc.stop(), 0) << plc.errorOutput();
    return status;
  }
};

TEST_F(ModbusLinkLossE2e, OnLossFaultEndsTheRunAsAPlcFault) {
  std::string out;
  EXPECT_EQ(testScenario("fault", "faults:\n  - {link: plc, comm_loss: [{at: 0.5 s, duration: 1 s}]}\nexpect:\n  - {run_end: plc_fault}\n", out), 0)
      << out;
  EXPECT_NE(out.find("PASS  loss"), std::string::npos) << out;
  // It ended at the window's first tick, not later.
  EXPECT_NE(out.find("at 0.5 s)"), std::string::npos) << out;
  // Without the cut the same assertion fails: the run completes its cycles.
  out.clear();
  EXPECT_EQ(testScenario("fault", "expect:\n  - {run_end: plc_fault}\n", out), 5) << out;
  EXPECT_NE(out.find("FAIL  loss"), std::string::npos) << out;
  EXPECT_NE(out.find("completed at "), std::string::npos) << out;
}

TEST_F(ModbusLinkLossE2e, OnLossHoldStallsTheCycleForTheWindowThenGoesOn) {
  const std::string expect = "expect:\n  - {run_end: completed}\n";
  // When the scenario's run ended ("completed at T s" of its PASS line), or -1.
  auto completedAt = [](const std::string& out) {
    const size_t at = out.find("completed at ");
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 13));
  };
  std::string held, plain;
  EXPECT_EQ(testScenario("hold", "faults:\n  - {link: plc, comm_loss: [{at: 0.3 s, duration: 2 s}]}\n" + expect, held), 0) << held;
  EXPECT_NE(held.find("PASS  loss"), std::string::npos) << held;
  EXPECT_EQ(testScenario("hold", expect, plain), 0) << plain;
  // Cut for 2 s, the cell waits (the devices keep their last commands, the PLC sees no status
  // change) and the run completes the same cycles about 2 s later.
  EXPECT_GT(completedAt(plain), 0.0) << plain;
  EXPECT_GE(completedAt(held), completedAt(plain) + 1.5) << held << plain;
}

}  // namespace
