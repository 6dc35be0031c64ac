// The ADS client bridge against the ADS server on loopback (a hand-made symbol table): every
// problem is found at start (refused connection, unknown names, wrong type or size, read-only
// targets), values cross by handle with one sum read per step and writes only on change, the
// handles are released when the simulation stops, and a lost link fails or is held.
#include "proto/ads/client_bridge.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "ads_test_support.hpp"
#include "proto/ads/entries.hpp"
#include "proto/ads/server.hpp"

namespace virtcom::proto::ads {
namespace {

using Problem = ClientBridge::Problem;

//   MAIN.count INT @32, MAIN.serial DINT @36 (read-only), MAIN.p ST_P @40, MAIN.flag BOOL @44,
//   MAIN.odd "INT" of 4 bytes @48 (a type and size that disagree), MAIN.speed LREAL @56
SymbolTable bridgeTable() {
  std::vector<Symbol> symbols = {
      {"MAIN.count", "INT", 0x4040, 32, 2, adst::kInt16, 0},
      {"MAIN.serial", "DINT", 0x4040, 36, 4, adst::kInt32, kSymbolFlagReadOnly},
      {"MAIN.p", "ST_P", 0x4040, 40, 4, adst::kBigType, 0},
      {"MAIN.flag", "BOOL", 0x4040, 44, 1, adst::kBit, 0},
      {"MAIN.odd", "INT", 0x4040, 48, 4, adst::kInt16, 0},
      {"MAIN.speed", "LREAL", 0x4040, 56, 8, adst::kReal64, 0},
  };
  std::vector<DataType> types = {
      {"INT", "", 2, adst::kInt16, kTypeFlagDataType, {}, {}, {}},
      {"ST_P", "", 4, adst::kBigType, kTypeFlagDataType, {}, {{"x", "INT", 2, 0, adst::kInt16}, {"y", "INT", 2, 2, adst::kInt16}}, {}},
  };
  MemoryLayout layout{64, {16, 4}, {20, 4}, {24, 8}, {{36, 4}}};
  auto resolver = [symbols](std::string_view path) -> std::optional<Symbol> {
    for (const Symbol& s : symbols)
      if (lowerCase(s.name) == lowerCase(path)) return s;
    if (lowerCase(path) == "main.p.x") return Symbol{"MAIN.p.x", "INT", 0x4040, 40, 2, adst::kInt16, 0};
    return std::nullopt;
  };
  return SymbolTable(symbols, types, layout, resolver);
}

class ClientBridgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ServerConfig config;
    config.listen = {0x7f000001, 0};
    auto server = Server::start(config, table_);
    ASSERT_TRUE(server) << server.error();
    server_ = std::move(*server);
    image_.assign(64, 0);
    setInt16(32, 1234);
    publish();
    command_ = bus_.add("Clamp.programNumber", ElemType::Int);  // read from the PLC
    done_ = bus_.add("Clamp.done", ElemType::Bool);             // written to the PLC
    force_ = bus_.add("Press.actualForce", ElemType::Lreal);    // written to the PLC
  }

  void setInt16(size_t at, int16_t v) { std::memcpy(image_.data() + at, &v, 2); }
  void publish() { server_->publishSnapshot(image_, 5); }
  // The scan side: takes the queued writes into image_ (as before a scan) and publishes it.
  size_t scan() {
    size_t edits = server_->applyPendingWrites({image_, {image_.data() + 16, 4}});
    publish();
    return edits;
  }

  BridgeConfig config(std::vector<BridgeSignal> signals) {
    BridgeConfig c;
    c.client.router = server_->endpoint();
    c.signals = std::move(signals);
    c.report = [this](const std::string& line) { reports_.push_back(line); };
    return c;
  }
  std::vector<BridgeSignal> wired() {
    return {{"MAIN.count", "Clamp.programNumber", command_, false, false},
            {"MAIN.flag", "Clamp.done", done_, true, false},
            {"MAIN.speed", "Press.actualForce", force_, true, false}};
  }

  SymbolTable table_ = bridgeTable();
  std::unique_ptr<Server> server_;
  std::vector<uint8_t> image_;
  TagBus bus_;
  TagId command_ = kNoTag, done_ = kNoTag, force_ = kNoTag;
  std::vector<std::string> reports_;
};

TEST_F(ClientBridgeTest, ARefusedConnectionIsReportedAtStart) {
  auto c = config(wired());
  c.client.router.port = server_->endpoint().port;
  server_->stop();
  server_.reset();  // nothing listens there any more
  ClientBridge::StartReport report;
  auto& problems = report.problems;
  EXPECT_EQ(ClientBridge::start(c, bus_, report), nullptr);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].signal, ClientBridge::kNoSignal);
  EXPECT_EQ(problems[0].kind, Problem::Kind::Link);
  EXPECT_NE(problems[0].text.find("ads: cannot connect to the PLC at 127.0.0.1:"), std::string::npos) << problems[0].text;
  EXPECT_NE(problems[0].text.find("Connection refused"), std::string::npos) << problems[0].text;
}

TEST_F(ClientBridgeTest, AWrongTargetIsOneProblemNotOnePerVariable) {
  ClientBridge::StartReport report;
  auto c = config(wired());
  c.client.target.port = 852;  // no PLC runtime 2 there
  EXPECT_EQ(ClientBridge::start(c, bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].signal, ClientBridge::kNoSignal);
  EXPECT_EQ(report.problems[0].text, "ads: the PLC at 127.0.0.1:" + std::to_string(server_->endpoint().port) +
                                         " (AmsNetId 127.0.0.1.1.1, port 852) refused the first request: 0x6 target port not "
                                         "found (check 'netid' and 'port')");
}

TEST_F(ClientBridgeTest, EveryUnknownOrMismatchedVariableIsReportedAtStartInOnePass) {
  TagId busy = bus_.add("Clamp.busy", ElemType::Bool), error = bus_.add("Clamp.error", ElemType::Int);
  ClientBridge::StartReport report;
  auto& problems = report.problems;
  auto bridge = ClientBridge::start(config({{"MAIN.nothing", "Clamp.execute", done_, false, false},  // 0: unknown
                                            {"MAIN.odd", "Clamp.programNumber", command_, false, false},  // 1: 4-byte INT
                                            {"MAIN.count", "Clamp.busy", busy, true, false},  // 2: INT for a BOOL port
                                            {"MAIN.p", "Clamp.error", error, true, false},    // 3: a struct
                                            {"MAIN.serial", "Clamp.error", error, true, false},  // 4: read-only
                                            {"MAIN.absent", "Clamp.error", error, true, true},   // optional: fine
                                            {"MAIN.p.x", "Clamp.error", error, true, false}}),   // a member: fine
                                    bus_, report);
  EXPECT_EQ(bridge, nullptr);
  ASSERT_EQ(problems.size(), 5u);
  EXPECT_EQ(report.found, (std::vector<bool>{false, true, true, true, true, false, true}));
  std::vector<std::pair<size_t, std::string>> expected = {
      {0, "ads: the PLC has no variable 'MAIN.nothing' to wire to Clamp.execute"},
      {1, "ads: 'MAIN.odd' is INT of 4 bytes on the PLC, expected 2"},
      {2, "ads: 'MAIN.count' is INT on the PLC but output 'Clamp.busy' is BOOL"},
      {3, "ads: 'MAIN.p' is a ST_P on the PLC; only BOOL, numeric and enum variables can be wired"},
      {4, "ads: 'MAIN.serial' is read-only on the PLC and cannot receive Clamp.error"},
  };
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(problems[i].signal, expected[i].first);
    EXPECT_EQ(problems[i].text, expected[i].second);
    EXPECT_EQ(problems[i].kind, i == 0 ? Problem::Kind::Unknown : Problem::Kind::Mismatch);
  }
}

TEST_F(ClientBridgeTest, ValuesCrossByHandleAndWritesHappenOnlyOnChange) {
  ClientBridge::StartReport report;
  auto& problems = report.problems;
  auto bridge = ClientBridge::start(config(wired()), bus_, report);
  ASSERT_NE(bridge, nullptr) << (problems.empty() ? "" : problems[0].text);
  const uint64_t afterStart = bridge->requests();  // one symbol info and one handle per signal
  EXPECT_EQ(afterStart, 6u);
  // Step 1: the sum read brings MAIN.count; the first push writes every output (one sum write).
  ASSERT_TRUE(bridge->pull(bus_, 0)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(command_), 1234);
  bus_.setBool(done_, true);
  bus_.setReal(force_, 2.5);
  bridge->push(bus_, 0);
  EXPECT_EQ(bridge->requests(), afterStart + 2);
  EXPECT_GT(scan(), 0u);
  EXPECT_EQ(image_[44], 1);
  double speed = 0;
  std::memcpy(&speed, image_.data() + 56, 8);
  EXPECT_EQ(speed, 2.5);
  // Step 2: nothing changed, so only the read goes out; the PLC's new value comes in.
  setInt16(32, -7);
  publish();
  ASSERT_TRUE(bridge->pull(bus_, 10));
  bridge->push(bus_, 10);
  EXPECT_EQ(bus_.getInt(command_), -7);
  EXPECT_EQ(bridge->requests(), afterStart + 3);
  // Step 3: one output changed: one plain Write by handle.
  ASSERT_TRUE(bridge->pull(bus_, 20));
  bus_.setBool(done_, false);
  bridge->push(bus_, 20);
  EXPECT_EQ(bridge->requests(), afterStart + 5);
  scan();
  EXPECT_EQ(image_[44], 0);
  EXPECT_TRUE(bridge->failure().empty());
}

TEST_F(ClientBridgeTest, ObservedVariablesGetATagOfTheirType) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config({{"MAIN.count", "", kNoTag, false, false}}), bus_, report);
  ASSERT_NE(bridge, nullptr);
  TagId tag = bridge->tag(0);
  ASSERT_NE(tag, kNoTag);
  EXPECT_EQ(bus_.name(tag), "MAIN.count");
  EXPECT_EQ(bus_.type(tag), ElemType::Int);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  EXPECT_EQ(bus_.getInt(tag), 1234);
}

TEST_F(ClientBridgeTest, StoppingReleasesTheHandlesAndDisconnects) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config(wired()), bus_, report);
  ASSERT_NE(bridge, nullptr);
  EXPECT_EQ(server_->connectionCount(), 1u);
  const uint64_t before = bridge->requests();
  bridge->simulationStopped();
  EXPECT_EQ(bridge->requests(), before + 1);  // one sum write of three 0xF006 items
  auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (server_->connectionCount() != 0 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(server_->connectionCount(), 0u);
}

TEST_F(ClientBridgeTest, ALostLinkFailsTheRunWithOnLossFault) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config(wired()), bus_, report);
  ASSERT_NE(bridge, nullptr);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  server_->stop();
  EXPECT_FALSE(bridge->pull(bus_, 10));
  EXPECT_NE(bridge->failure().find("ads: link to the PLC at 127.0.0.1:"), std::string::npos) << bridge->failure();
  EXPECT_NE(bridge->failure().find(" lost: reading the PLC's outputs: "), std::string::npos) << bridge->failure();
  EXPECT_TRUE(reports_.empty());
}

TEST_F(ClientBridgeTest, ALostLinkIsHeldWithOnLossHoldAndTheBridgeReconnects) {
  ClientBridge::StartReport report;
  auto c = config(wired());
  c.faultOnLoss = false;
  auto bridge = ClientBridge::start(c, bus_, report);
  ASSERT_NE(bridge, nullptr);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  bus_.setBool(done_, true);
  bridge->push(bus_, 0);
  const uint16_t port = server_->endpoint().port;
  server_.reset();  // the PLC is gone: closed connections, nothing listening
  EXPECT_TRUE(bridge->pull(bus_, 10));
  bridge->push(bus_, 10);
  EXPECT_TRUE(bridge->pull(bus_, 20));  // retried, refused: reported once
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_NE(reports_[0].find("(holding the last commands, retrying every step)"), std::string::npos) << reports_[0];
  EXPECT_EQ(bus_.getInt(command_), 1234);  // the last command is held
  // The PLC is back (a fresh one, which knows nothing of the old handles or values).
  ServerConfig again;
  again.listen = {0x7f000001, port};
  auto server = Server::start(again, table_);
  ASSERT_TRUE(server) << server.error();
  server_ = std::move(*server);
  image_.assign(64, 0);
  setInt16(32, 99);
  publish();
  EXPECT_TRUE(bridge->pull(bus_, 30));
  EXPECT_EQ(bus_.getInt(command_), 99);
  bridge->push(bus_, 30);  // every output again, changed or not
  scan();
  EXPECT_EQ(image_[44], 1);
  ASSERT_EQ(reports_.size(), 2u);
  EXPECT_NE(reports_[1].find("ads: reconnected to the PLC at 127.0.0.1:"), std::string::npos) << reports_[1];
  EXPECT_TRUE(bridge->failure().empty());
}

TEST(SymbolEntry, ParsesWhatTheServerWrites) {
  std::vector<uint8_t> entry;
  appendSymbolEntry(entry, {"MAIN.Robot1.busy", "BOOL", 0x4040, 17, 1, adst::kBit, kSymbolFlagReadOnly});
  auto s = parseSymbolEntry(entry);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->name, "MAIN.Robot1.busy");
  EXPECT_EQ(s->type, "BOOL");
  EXPECT_EQ(s->indexGroup, 0x4040u);
  EXPECT_EQ(s->indexOffset, 17u);
  EXPECT_EQ(s->size, 1u);
  EXPECT_EQ(s->adsType, adst::kBit);
  EXPECT_EQ(s->flags, kSymbolFlagReadOnly);
  for (size_t cut = 0; cut < 30 + 17; ++cut)  // every truncation of the fixed part and the strings
    EXPECT_FALSE(parseSymbolEntry({entry.data(), cut})) << cut;
}

}  // namespace
}  // namespace virtcom::proto::ads
