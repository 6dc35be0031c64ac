// Signals between the tag bus and Modbus tables: the codec (types, word order, scaling,
// clamping), the served cell's bridge, and the client bridge against a real server on loopback
// (reads, change-only writes, connection loss with both policies).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "core/write_audit.hpp"
#include "proto/modbus/audited_signals.hpp"
#include "proto/modbus/client_bridge.hpp"
#include "proto/modbus/server.hpp"
#include "proto/modbus/signal_codec.hpp"
#include "proto/modbus/signal_server.hpp"

namespace virtcom::proto::modbus {
namespace {

MapEntry entry(TagId tag, SignalDir dir, Table table, uint16_t address, ValueType type,
               WordOrder order = WordOrder::HighFirst, double scale = 1) {
  MapEntry e;
  e.tag = tag;
  e.signal = "S" + std::to_string(tag);
  e.dir = dir;
  e.table = table;
  e.address = address;
  e.type = type;
  e.order = order;
  e.scale = scale;
  e.readOnly = dir == SignalDir::Status;
  return e;
}

std::vector<uint16_t> registers(const ImageView& v, Table t, uint32_t from, uint32_t count) {
  std::vector<uint16_t> out;
  for (uint32_t r = from; r < from + count; ++r) out.push_back(getRegister(tableBytes(v, t), r));
  return out;
}

TEST(SignalCodec, RealInBothWordOrders) {
  TagBus bus;
  TagId force = bus.add("Press.actualForce", ElemType::Lreal);
  SignalMap map{{entry(force, SignalDir::Status, Table::InputRegister, 0, ValueType::Real),
                 entry(force, SignalDir::Status, Table::InputRegister, 2, ValueType::Real, WordOrder::LowFirst)}};
  TableImage tables(tablesFor(map));
  bus.setReal(force, 1.5);  // 0x3FC00000
  for (const auto& e : map.entries) storeSignal(e, bus, tables.view());
  EXPECT_EQ(registers(tables.view(), Table::InputRegister, 0, 4), (std::vector<uint16_t>{0x3FC0, 0x0000, 0x0000, 0x3FC0}));
  TagBus back;
  TagId t = back.add("x", ElemType::Lreal);
  MapEntry e = map.entries[1];
  e.tag = t;
  loadSignal(e, tables.view(), back);
  EXPECT_EQ(back.getReal(t), 1.5);
}

TEST(SignalCodec, ScaledIntegersRoundAndClampToTheirType) {
  TagBus bus;
  TagId pos = bus.add("Axis.position", ElemType::Lreal);
  MapEntry tenths = entry(pos, SignalDir::Status, Table::HoldingRegister, 0, ValueType::Int, WordOrder::HighFirst, 0.1);
  MapEntry dint = entry(pos, SignalDir::Status, Table::HoldingRegister, 1, ValueType::Dint);
  MapEntry uint = entry(pos, SignalDir::Status, Table::HoldingRegister, 3, ValueType::Uint);
  TableImage tables(tablesFor(SignalMap{{tenths, dint, uint}}));
  bus.setReal(pos, -12.34);
  for (const auto& e : {tenths, dint, uint}) storeSignal(e, bus, tables.view());
  EXPECT_EQ(registers(tables.view(), Table::HoldingRegister, 0, 4), (std::vector<uint16_t>{0xFF85, 0xFFFF, 0xFFF4, 0x0000}));
  bus.setReal(pos, 1e9);  // beyond INT: clamped, not wrapped
  storeSignal(tenths, bus, tables.view());
  EXPECT_EQ(registers(tables.view(), Table::HoldingRegister, 0, 1), (std::vector<uint16_t>{0x7FFF}));
  loadSignal(tenths, tables.view(), bus);
  EXPECT_DOUBLE_EQ(bus.getReal(pos), 3276.7);
}

TEST(SignalCodec, BoolsInBitsAndInRegisters) {
  TagBus bus;
  TagId done = bus.add("Clamp.done", ElemType::Bool);
  MapEntry bit = entry(done, SignalDir::Status, Table::DiscreteInput, 9, ValueType::Bool);
  MapEntry word = entry(done, SignalDir::Status, Table::HoldingRegister, 0, ValueType::Uint);
  TableImage tables(tablesFor(SignalMap{{bit, word}}));
  bus.setBool(done, true);
  storeSignal(bit, bus, tables.view());
  storeSignal(word, bus, tables.view());
  EXPECT_EQ(tables.view().inputs[1], 0x02);
  EXPECT_EQ(registers(tables.view(), Table::HoldingRegister, 0, 1), (std::vector<uint16_t>{1}));
}

TEST(SignalCodec, TablesForMarksReadOnlyEntries) {
  ImageShape shape = tablesFor(SignalMap{{entry(0, SignalDir::Command, Table::Coil, 3, ValueType::Bool),
                                          entry(1, SignalDir::Status, Table::Coil, 9, ValueType::Bool),
                                          entry(2, SignalDir::Status, Table::HoldingRegister, 4, ValueType::Real)}});
  EXPECT_EQ(shape.outputs, 2u);
  EXPECT_EQ(shape.memory, 12u);
  EXPECT_EQ(shape.readOnlyCoils, (std::vector<uint8_t>{0x00, 0x02}));
  EXPECT_EQ(shape.readOnlyHolding, (std::vector<uint8_t>{0x30}));
}

// An OpenPLC-mapped server like `virtcom exec --modbus` (the external PLC) on a free port.
class ClientBridgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    execute_ = bus_.add("Clamp.execute", ElemType::Bool);
    program_ = bus_.add("Clamp.programNumber", ElemType::Int);
    done_ = bus_.add("Clamp.done", ElemType::Bool);
    force_ = bus_.add("Press.actualForce", ElemType::Lreal);
    startServer(0);
  }

  void startServer(uint16_t port) {
    ServerConfig config;
    config.listen = {0x7f000001, port};
    ImageShape shape;
    shape.inputs = shape.outputs = shape.memory = 16;
    auto s = Server::start(config, shape);
    ASSERT_TRUE(s) << s.error();
    server_ = std::move(*s);
    server_->publishSnapshot(live());
  }

  ImageView live() { return {inputs_, outputs_, memory_}; }

  ClientConfig config(bool faultOnLoss) {
    ClientConfig c;
    c.peer = server_->endpoint();
    c.pollNs = 10;
    c.timeoutNs = 2'000'000'000;
    c.faultOnLoss = faultOnLoss;
    c.map.entries = {entry(execute_, SignalDir::Command, Table::Coil, 0, ValueType::Bool),
                     entry(program_, SignalDir::Command, Table::HoldingRegister, 1, ValueType::Int),
                     entry(done_, SignalDir::Status, Table::HoldingRegister, 1024, ValueType::Int),
                     entry(force_, SignalDir::Status, Table::HoldingRegister, 2050, ValueType::Real)};
    c.report = [this](const std::string& line) { reports_.push_back(line); };
    return c;
  }

  // One poll at `nowNs`: pull, then push; the server's scan side applies what was written.
  bool poll(ClientBridge& bridge, int64_t nowNs) {
    bool ok = bridge.pull(bus_, nowNs);
    bridge.push(bus_, nowNs);
    if (server_) {
      server_->applyPendingWrites(live());
      server_->publishSnapshot(live());
    }
    return ok;
  }

  TagBus bus_;
  TagId execute_ = 0, program_ = 0, done_ = 0, force_ = 0;
  std::array<uint8_t, 16> inputs_{}, outputs_{}, memory_{};
  std::unique_ptr<Server> server_;
  std::vector<std::string> reports_;
};

TEST_F(ClientBridgeTest, ReadsCommandsAndWritesOnlyChangedStatus) {
  outputs_[0] = 0x01;  // %QX0.0: coil 0
  outputs_[2] = 7;     // %QW1: holding 1
  server_->publishSnapshot(live());
  ClientBridge bridge(config(true));
  bus_.setBool(done_, true);
  bus_.setReal(force_, 1234.5);
  ASSERT_TRUE(poll(bridge, 0)) << bridge.failure();
  EXPECT_TRUE(bus_.getBool(execute_));
  EXPECT_EQ(bus_.getInt(program_), 7);
  EXPECT_EQ(memory_[0], 1);  // %MW0 = holding 1024
  float force = 0;
  uint32_t bits = uint32_t(memory_[4]) | uint32_t(memory_[5]) << 8 | uint32_t(memory_[6]) << 16 | uint32_t(memory_[7]) << 24;
  std::memcpy(&force, &bits, 4);  // %MD1 = holding 2050-2051
  EXPECT_EQ(force, 1234.5f);
  uint64_t first = bridge.requests();
  EXPECT_EQ(first, 4u);  // two read blocks (coils, holding), two writes
  ASSERT_TRUE(poll(bridge, 5));  // not a poll time yet: no request
  EXPECT_EQ(bridge.requests(), first);
  ASSERT_TRUE(poll(bridge, 10));  // nothing changed: only the reads
  EXPECT_EQ(bridge.requests(), first + 2);
  bus_.setBool(done_, false);
  ASSERT_TRUE(poll(bridge, 20));
  EXPECT_EQ(bridge.requests(), first + 5);
  EXPECT_EQ(memory_[0], 0);
}

TEST_F(ClientBridgeTest, ALostLinkIsAFaultByDefault) {
  ClientBridge bridge(config(true));
  ASSERT_TRUE(poll(bridge, 0));
  server_.reset();
  EXPECT_FALSE(poll(bridge, 10) && poll(bridge, 20));  // the loss shows at the latest on the next request
  EXPECT_NE(bridge.failure().find("link to the PLC at 127.0.0.1:"), std::string::npos) << bridge.failure();
  EXPECT_NE(bridge.failure().find(" lost: "), std::string::npos) << bridge.failure();
  EXPECT_TRUE(reports_.empty());
}

TEST_F(ClientBridgeTest, OnLossHoldKeepsTheCommandsAndReconnects) {
  outputs_[0] = 0x01;
  server_->publishSnapshot(live());
  ClientBridge bridge(config(false));
  bus_.setBool(done_, true);
  ASSERT_TRUE(poll(bridge, 0));
  uint16_t port = server_->endpoint().port;
  server_.reset();
  memory_ = {};
  for (int64_t t = 10; t <= 30; t += 10) ASSERT_TRUE(bridge.pull(bus_, t)) << bridge.failure();
  EXPECT_TRUE(bus_.getBool(execute_));  // held
  ASSERT_EQ(reports_.size(), 1u);       // reported once
  EXPECT_NE(reports_[0].find("holding the last commands"), std::string::npos) << reports_[0];
  startServer(port);
  ASSERT_TRUE(poll(bridge, 40)) << bridge.failure();
  ASSERT_EQ(reports_.size(), 2u);
  EXPECT_NE(reports_[1].find("reconnected"), std::string::npos);
  EXPECT_EQ(memory_[0], 1);  // unchanged status is written again after reconnecting
}

TEST_F(ClientBridgeTest, AnAddressThePlcLacksIsAFaultEvenWhenHolding) {
  ClientConfig c = config(false);
  c.map.entries[1].address = 900;  // %QW900 is outside a 16-byte image
  ClientBridge bridge(c);
  EXPECT_FALSE(poll(bridge, 0));
  EXPECT_NE(bridge.failure().find("refused reading holding 900..900: Illegal data address"), std::string::npos) << bridge.failure();
}

// The served cell: clients write commands into the tables, status comes out of the bus.
TEST(SignalServerTest, PullLoadsWrittenCommandsAndPushPublishesStatus) {
  TagBus bus;
  TagId execute = bus.add("Clamp.execute", ElemType::Bool);
  TagId done = bus.add("Clamp.done", ElemType::Bool);
  SignalMap map{{entry(execute, SignalDir::Command, Table::Coil, 0, ValueType::Bool),
                 entry(done, SignalDir::Status, Table::DiscreteInput, 0, ValueType::Bool)}};
  ServerConfig config;
  config.listen = {0x7f000001, 0};
  auto server = SignalServer::start(config, map);
  ASSERT_TRUE(server) << server.error();
  ClientConfig c;  // a libmodbus client through the client bridge, as an external PLC would be
  c.peer = (*server)->endpoint();
  c.map.entries = {entry(done, SignalDir::Command, Table::DiscreteInput, 0, ValueType::Bool),
                   entry(execute, SignalDir::Status, Table::Coil, 0, ValueType::Bool)};
  TagBus plc;
  TagId plcExecute = plc.add("execute", ElemType::Bool);
  TagId plcDone = plc.add("done", ElemType::Bool);
  c.map.entries[0].tag = plcDone;
  c.map.entries[1].tag = plcExecute;
  ClientBridge client(c);
  plc.setBool(plcExecute, true);
  ASSERT_TRUE(client.pull(plc, 0));
  client.push(plc, 0);  // the write is queued for the next tick
  ASSERT_TRUE((*server)->pull(bus, 0));
  EXPECT_TRUE(bus.getBool(execute));
  bus.setBool(done, true);
  (*server)->push(bus, 0);
  ASSERT_TRUE(client.pull(plc, 10'000'000));
  EXPECT_TRUE(plc.getBool(plcDone));
}

// `serve --modbus`: what the external PLC (or any client) writes into the cell's signals is
// audited as the soft PLC's writes are, each record naming the signal, its table and address,
// and its value as the signal (scaled), at the virtual time of the tick it landed in.
TEST(SignalServerTest, ItsClientsWritesAreAuditedAsTheSignalsTheyChange) {
  TagBus bus;
  TagId execute = bus.add("Clamp.execute", ElemType::Bool);
  TagId target = bus.add("Axis.target", ElemType::Lreal);
  TagId speed = bus.add("Axis.speed", ElemType::Lreal);
  SignalMap map{{entry(execute, SignalDir::Command, Table::Coil, 3, ValueType::Bool),
                 entry(target, SignalDir::Command, Table::HoldingRegister, 4, ValueType::Real),
                 entry(speed, SignalDir::Command, Table::HoldingRegister, 6, ValueType::Int, WordOrder::HighFirst, 0.1)}};
  for (MapEntry& e : map.entries) e.signal = bus.name(e.tag);
  ServerConfig config;
  config.listen = {0x7f000001, 0};
  auto server = SignalServer::start(config, map);
  ASSERT_TRUE(server) << server.error();
  std::vector<WriteRecord> records;
  WriteAudit audit(auditedSignals(map), [&](const WriteRecord& r) { records.push_back(r); });
  (*server)->auditWrites(&audit);
  ClientConfig c;
  c.peer = (*server)->endpoint();
  TagBus plc;
  c.map.entries = {entry(plc.add("execute", ElemType::Bool), SignalDir::Status, Table::Coil, 3, ValueType::Bool),
                   entry(plc.add("target", ElemType::Lreal), SignalDir::Status, Table::HoldingRegister, 4, ValueType::Real),
                   entry(plc.add("speed", ElemType::Lreal), SignalDir::Status, Table::HoldingRegister, 6, ValueType::Int,
                         WordOrder::HighFirst, 0.1)};
  ClientBridge client(c);
  plc.setBool(c.map.entries[0].tag, true);
  plc.setReal(c.map.entries[1].tag, 2.5);
  plc.setReal(c.map.entries[2].tag, 12.5);
  ASSERT_TRUE(client.pull(plc, 0));
  client.push(plc, 0);
  ASSERT_TRUE((*server)->pull(bus, 5'000'000));
  EXPECT_DOUBLE_EQ(bus.getReal(speed), 12.5);
  ASSERT_EQ(records.size(), 3u);
  std::vector<std::string> lines;
  for (const WriteRecord& r : records) {
    EXPECT_EQ(r.virtualNs, 5'000'000);
    EXPECT_EQ(r.writer.protocol, WriteProtocol::Modbus);
    lines.push_back(writtenVariableText(r) + ": " + r.oldValue + " -> " + r.newValue);
  }
  std::sort(lines.begin(), lines.end());
  EXPECT_EQ(lines, (std::vector<std::string>{"Axis.speed (holding 6): 0 -> 12.5", "Axis.target (holding 4): 0 -> 2.5",
                                             "Clamp.execute (coil 3): FALSE -> TRUE"}));
  EXPECT_EQ(audit.count(WriteProtocol::Modbus), 3u);
}

}  // namespace
}  // namespace virtcom::proto::modbus
