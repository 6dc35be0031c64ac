// End-to-end: `virtcom exec modbus_io.st --modbus 127.0.0.1:0` in its own process, driven by the
// libmodbus client API and by Debian's mbpoll over loopback. Port 0 lets the server pick a free
// port, which it announces on stderr ("modbus: serving on 127.0.0.1:PORT"). Every wait polls
// with a deadline; every test ends with SIGTERM and expects exit status 0.
#include <modbus.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "modbus_client.hpp"
#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/eventually.hpp"
#include "support/loopback_client.hpp"

namespace {

using virtcom::e2e::connectModbus;
using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::eventually;
using virtcom::test::LoopbackClient;

const char* const kExe = VIRTCOM_EXE;
const char* const kDataDir = VIRTCOM_E2E_DATA;

// Holding registers of modbus_io.st (OpenPLC mapping).
constexpr int kCountRegister = 1;      // %QW1: scans so far
constexpr int kDoubledRegister = 2;    // %QW2 := %MW0 * 2
constexpr int kSetpointRegister = 1024;  // %MW0

class ModbusE2e : public ::testing::Test {
 protected:
  virtual std::vector<std::string> execArgs() const {
    return {"exec", "modbus_io.st", "--modbus", "127.0.0.1:0", "--set", "MAIN.inWord=7"};
  }

  void SetUp() override {
    plc_ = std::make_unique<ServerProcess>(kExe, execArgs(), kDataDir, "modbus: serving on ");
    port_ = plc_->port();
    ASSERT_GT(port_, 0) << "no 'modbus: serving on' line; stderr so far:\n" << plc_->errorOutput();
  }

  void TearDown() override {
    if (port_ > 0) {
      EXPECT_EQ(plc_->stop(), 0) << plc_->errorOutput();
    }
  }

  modbus_t* connect() {
    modbus_t* ctx = connectModbus(port_);
    if (ctx) contexts_.push_back(ctx);
    return ctx;
  }

  // Polls holding register `reg` until it is at least `want` (the program's registers only grow);
  // the last value read.
  int awaitRegister(modbus_t* ctx, int reg, int want) {
    uint16_t v = 0;
    eventually([&] { return modbus_read_registers(ctx, reg, 1, &v) == 1 && v >= want; });
    return v;
  }

 public:
  ~ModbusE2e() override {
    for (modbus_t* ctx : contexts_) {
      modbus_close(ctx);
      modbus_free(ctx);
    }
  }

 protected:
  std::unique_ptr<ServerProcess> plc_;
  int port_ = 0;
  std::vector<modbus_t*> contexts_;
};

TEST_F(ModbusE2e, LibmodbusReadsTheImageAndThePlcReactsToWrites) {
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr) << modbus_strerror(errno);
  // The server answers from the cold-start image until the first scan has run.
  ASSERT_GE(awaitRegister(ctx, kCountRegister, 2), 2);
  uint8_t coils[8] = {};
  ASSERT_EQ(modbus_read_bits(ctx, 0, 8, coils), 8) << modbus_strerror(errno);
  EXPECT_EQ(coils[1], 1);  // lamp AT %QX0.1 := NOT inBit
  uint8_t inputs[8] = {};
  ASSERT_EQ(modbus_read_input_bits(ctx, 0, 8, inputs), 8);
  EXPECT_EQ(inputs[0], 0);
  uint16_t inWord = 0;
  ASSERT_EQ(modbus_read_input_registers(ctx, 1, 1, &inWord), 1);
  EXPECT_EQ(inWord, 7);  // --set MAIN.inWord=7 at %IW1

  // The scan counter advances while we watch: the PLC runs paced.
  uint16_t first = 0;
  ASSERT_EQ(modbus_read_registers(ctx, kCountRegister, 1, &first), 1);
  EXPECT_GE(awaitRegister(ctx, kCountRegister, first + 2), first + 2);

  ASSERT_EQ(modbus_write_register(ctx, kSetpointRegister, 21), 1) << modbus_strerror(errno);
  EXPECT_EQ(awaitRegister(ctx, kDoubledRegister, 42), 42);
  uint16_t values[] = {50}, readBack[2] = {};
  ASSERT_EQ(modbus_write_and_read_registers(ctx, kSetpointRegister, 1, values, kSetpointRegister, 2, readBack), 2);
  EXPECT_EQ(readBack[0], 50);
  EXPECT_EQ(awaitRegister(ctx, kDoubledRegister, 100), 100);
  ASSERT_EQ(modbus_write_registers(ctx, kSetpointRegister, 1, values), 1);

  // Coil 8 (%QX1.0) is not written by the program, so it keeps what the client wrote.
  ASSERT_EQ(modbus_write_bit(ctx, 8, 1), 1);
  uint8_t data[] = {1, 0, 1};
  ASSERT_EQ(modbus_write_bits(ctx, 9, 3, data), 3);
  uint8_t back[4] = {};
  ASSERT_EQ(modbus_read_bits(ctx, 8, 4, back), 4);
  EXPECT_EQ(back[0], 1);
  EXPECT_EQ(back[1], 1);
  EXPECT_EQ(back[2], 0);
  EXPECT_EQ(back[3], 1);

  uint16_t none = 0;
  EXPECT_EQ(modbus_read_registers(ctx, 600, 1, &none), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_read_input_registers(ctx, 60000, 1, &none), -1);
  EXPECT_EQ(errno, EMBXILADD);
}

// exec --modbus-writable-inputs: a client playing the field writes %IW/%IX through holding
// registers 8192.. (docs/modbus.md); the FC2/FC4 tables still show the same bytes.
class ModbusWritableInputsE2e : public ModbusE2e {
 protected:
  std::vector<std::string> execArgs() const override {
    return {"exec", "modbus_io.st", "--modbus", "127.0.0.1:0", "--modbus-writable-inputs"};
  }
};

TEST_F(ModbusE2e, InputsAreNotWritableByDefault) {
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr) << modbus_strerror(errno);
  EXPECT_EQ(modbus_write_register(ctx, 8192, 1), -1);
  EXPECT_EQ(errno, EMBXILADD);
}

TEST_F(ModbusWritableInputsE2e, ClientWritesInputsThroughHoldingRegisters) {
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr) << modbus_strerror(errno);
  ASSERT_GE(awaitRegister(ctx, kCountRegister, 2), 2);
  uint8_t lamp = 0;
  ASSERT_EQ(modbus_read_bits(ctx, 1, 1, &lamp), 1);
  EXPECT_EQ(lamp, 1);  // lamp AT %QX0.1 := NOT inBit, inBit AT %IX0.0 still FALSE
  uint16_t field[] = {1, 99};  // register 8192 = %IW0 (bit 0 = %IX0.0), 8193 = %IW1 (inWord)
  ASSERT_EQ(modbus_write_registers(ctx, 8192, 2, field), 2) << modbus_strerror(errno);
  uint16_t inWord = 0;
  eventually([&] { return modbus_read_bits(ctx, 1, 1, &lamp) == 1 && lamp == 0; });
  EXPECT_EQ(lamp, 0);  // the program saw %IX0.0 = TRUE
  ASSERT_EQ(modbus_read_input_registers(ctx, 1, 1, &inWord), 1);
  EXPECT_EQ(inWord, 99);
  uint8_t inBit = 0;
  ASSERT_EQ(modbus_read_input_bits(ctx, 0, 1, &inBit), 1);
  EXPECT_EQ(inBit, 1);
}

// exec --modbus-readonly: reads as usual, every write function refused with exception 01
// (docs/security.md).
class ModbusReadOnlyE2e : public ModbusE2e {
 protected:
  std::vector<std::string> execArgs() const override {
    return {"exec", "modbus_io.st", "--modbus", "127.0.0.1:0", "--modbus-readonly"};
  }
};

TEST_F(ModbusReadOnlyE2e, WritesAreRefusedWithIllegalFunctionAndReadsWork) {
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr) << modbus_strerror(errno);
  EXPECT_GE(awaitRegister(ctx, kCountRegister, 2), 2);
  EXPECT_EQ(modbus_write_register(ctx, kSetpointRegister, 21), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  EXPECT_EQ(modbus_write_bit(ctx, 12, 1), -1);
  EXPECT_EQ(errno, EMBXILFUN);
}

// exec --audit-writes each: every write of a client on stderr with its peer, the variable (or the
// IEC address where none is declared) and the old and new value; the count at the end.
class ModbusAuditE2e : public ModbusE2e {
 protected:
  std::vector<std::string> execArgs() const override {
    return {"exec", "modbus_io.st", "--modbus", "127.0.0.1:0", "--audit-writes", "each"};
  }
};

TEST_F(ModbusAuditE2e, EachWriteIsLoggedWithPeerVariableAndValues) {
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr) << modbus_strerror(errno);
  ASSERT_EQ(modbus_write_register(ctx, kSetpointRegister, 21), 1) << modbus_strerror(errno);
  EXPECT_TRUE(plc_->waitFor("modbus 127.0.0.1:")) << plc_->errorOutput();
  EXPECT_TRUE(plc_->waitFor(" MAIN.setpoint (%MW0): 0 -> 21\n")) << plc_->errorOutput();
  ASSERT_EQ(modbus_write_bit(ctx, 8, 1), 1);
  EXPECT_TRUE(plc_->waitFor(" %QX1.0: FALSE -> TRUE\n")) << plc_->errorOutput();
  EXPECT_EQ(plc_->stop(), 0);
  port_ = 0;
  EXPECT_NE(plc_->errorOutput().find("audit: 2 external writes (ads 0, modbus 2, opcua 0, http 0)"), std::string::npos)
      << plc_->errorOutput();
}

// exec --modbus-allow without this machine: the loopback client is closed at once, and the
// refusal logged with the peer and the reason (docs/security.md).
class ModbusAllowListE2e : public ModbusE2e {
 protected:
  std::vector<std::string> execArgs() const override {
    return {"exec", "modbus_io.st", "--modbus", "127.0.0.1:0", "--modbus-allow", "10.0.0.0/8"};
  }
};

TEST_F(ModbusAllowListE2e, APeerOutsideTheListIsRefusedAndLogged) {
  LoopbackClient c(static_cast<uint16_t>(port_));
  ASSERT_TRUE(c.connected());
  EXPECT_TRUE(c.closedByServer());
  EXPECT_TRUE(plc_->waitFor("modbus: refused 127.0.0.1: not in --modbus-allow")) << plc_->errorOutput();
}

TEST_F(ModbusE2e, ManyClientsAndAbruptDisconnectsDoNotStopTheServer) {
  std::vector<modbus_t*> clients;
  for (int i = 0; i < 8; ++i) {
    clients.push_back(connect());
    ASSERT_NE(clients.back(), nullptr);
  }
  // A client that sends half a frame and resets the connection, and one that sends garbage.
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
      uint16_t regs[3];
      for (int k = 0; k < 50; ++k) ok[i] += modbus_read_registers(clients[i], 0, 3, regs) == 3;
    });
  for (auto& t : threads) t.join();
  for (size_t i = 0; i < clients.size(); ++i) EXPECT_EQ(ok[i], 50) << "client " << i;
  // One more client after all that still gets served.
  modbus_t* late = connect();
  ASSERT_NE(late, nullptr);
  uint16_t v = 0;
  EXPECT_EQ(modbus_read_registers(late, kSetpointRegister, 1, &v), 1);
}

TEST_F(ModbusE2e, MbpollReadsAndWritesEveryTable) {
  if (::access("/usr/bin/mbpoll", X_OK) != 0) {
    if (const char* require = std::getenv("VIRTCOM_REQUIRE_MBPOLL"); require && std::string(require) == "1")
      FAIL() << "mbpoll is not installed (apt-get install mbpoll) and VIRTCOM_REQUIRE_MBPOLL=1";
    GTEST_SKIP() << "mbpoll is not installed";
  }
  // -0: PDU addresses (0-based) as in docs/modbus.md; -1: poll once; -o: timeout in seconds.
  const std::string mbpoll = "/usr/bin/mbpoll -m tcp -a 1 -0 -1 -o 5 -p " + std::to_string(port_);
  std::string out;
  ASSERT_EQ(shell(mbpoll + " -t 4 -r 1024 127.0.0.1 21", out), 0) << out;  // write %MW0
  EXPECT_NE(out.find("Written 1 references"), std::string::npos) << out;
  modbus_t* ctx = connect();
  ASSERT_NE(ctx, nullptr);
  EXPECT_EQ(awaitRegister(ctx, kDoubledRegister, 42), 42);  // also: a scan has run
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 4 -r 2 127.0.0.1", out), 0) << out;  // holding: %QW2
  EXPECT_NE(out.find("[2]: \t42"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 3 -r 1 127.0.0.1", out), 0) << out;  // input register: %IW1
  EXPECT_NE(out.find("[1]: \t7"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 0 -r 1 127.0.0.1", out), 0) << out;  // coil: %QX0.1
  EXPECT_NE(out.find("[1]: \t1"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 1 -r 0 127.0.0.1", out), 0) << out;  // discrete input: %IX0.0
  EXPECT_NE(out.find("[0]: \t0"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 0 -r 12 127.0.0.1 1", out), 0) << out;  // write coil %QX1.4
  out.clear();
  ASSERT_EQ(shell(mbpoll + " -t 0 -r 12 127.0.0.1", out), 0) << out;
  EXPECT_NE(out.find("[12]: \t1"), std::string::npos) << out;
  out.clear();
  EXPECT_NE(shell(mbpoll + " -t 4 -r 600 127.0.0.1", out), 0) << out;
  EXPECT_NE(out.find("Illegal data address"), std::string::npos) << out;
}

}  // namespace
