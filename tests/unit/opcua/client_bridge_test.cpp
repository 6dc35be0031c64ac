// The OPC UA client and its bridge against our OPC UA server on loopback (the ADS test table,
// tests/unit/ads/ads_test_support.hpp): every problem is found at start (refused connection,
// malformed node ids, unknown nodes, wrong types, nodes this session may not write), values
// cross with one Read per poll and one Write of what changed, users log on with a password, and
// a lost link fails or is held and reconnected. With a subscription, the PLC's outputs come with
// the server's Publish responses, and a server that refuses subscriptions is read instead.
#include "proto/opcua/client_bridge.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "../ads/ads_test_support.hpp"
#include "support/eventually.hpp"
#include "proto/opcua/server.hpp"

namespace virtcom::proto::opcua {
namespace {

using Problem = ClientBridge::Problem;

std::string node(const std::string& path) { return "ns=4;s=|var|virtcom.Application." + path; }

class OpcuaBridgeTest : public ::testing::Test {
 protected:
  // On `port` (0: any free one); a port given: a restarted PLC, the old server stopped.
  void startServer(ServerConfig config, uint16_t port = 0) {
    config.listen = {0x7f000001, port};
    auto server = Server::start(config, table_);
    ASSERT_TRUE(server) << server.error();
    server_ = std::move(*server);
    publish();
  }
  // A restarted PLC on `port`; another application name gives its variables other node ids.
  void restartServer(uint16_t port, UserAccess anonymous, const std::string& applicationName = "virtcom") {
    ServerConfig again;
    again.anonymous = anonymous;
    again.names.applicationName = applicationName;
    startServer(again, port);
  }
  void SetUp() override {
    image_.assign(64, 0);
    setInt16(32, 1234);  // MAIN.count
    ServerConfig c;
    c.anonymous = UserAccess::Write;  // as `--opcua-anonymous write`
    startServer(c);
    program_ = bus_.add("Clamp.programNumber", ElemType::Int);  // read from the PLC
    position_ = bus_.add("Clamp.position", ElemType::Lreal);    // written to the PLC (an INT there)
  }

  void setInt16(size_t at, int16_t v) { std::memcpy(image_.data() + at, &v, 2); }
  int16_t int16At(size_t at) const {
    int16_t v = 0;
    std::memcpy(&v, image_.data() + at, 2);
    return v;
  }
  void publish() { server_->publishSnapshot(image_); }
  // The scan side: takes the queued writes into image_ (as before a scan) and publishes it.
  size_t scan() {
    size_t edits = server_->applyPendingWrites({image_, {image_.data() + 16, 4}});
    publish();
    return edits;
  }

  BridgeConfig config(std::vector<BridgeSignal> signals) {
    BridgeConfig c;
    c.client.server = server_->endpoint();
    c.client.endpointUrl = server_->endpointUrl();
    c.pollNs = 0;  // every step
    c.subscribe = false;  // the outputs read at each poll (OpcuaBridgeSubscriptionTest: published)
    c.signals = std::move(signals);
    c.report = [this](const std::string& line) { reports_.push_back(line); };
    return c;
  }
  std::vector<BridgeSignal> wiredByPath();  // wired(), by browse path
  std::vector<BridgeSignal> wired() {
    return {{node("MAIN.count"), "MAIN.count", "Clamp.programNumber", program_, false, false},
            {node("MAIN.p.x"), "MAIN.p.x", "Clamp.position", position_, true, false}};
  }

  ads::SymbolTable table_ = ads::testing::makeTable();
  std::unique_ptr<Server> server_;
  std::vector<uint8_t> image_;
  TagBus bus_;
  TagId program_ = kNoTag, position_ = kNoTag;
  std::vector<std::string> reports_;
};

TEST(OpcuaNodeIds, ParseTheNumericAndStringForms) {
  EXPECT_EQ(parseNodeId("i=85"), NodeId::num(0, 85));
  EXPECT_EQ(parseNodeId("ns=2;i=17"), NodeId::num(2, 17));
  EXPECT_EQ(parseNodeId("ns=4;s=|var|virtcom.Application.MAIN.x"), NodeId::str(4, "|var|virtcom.Application.MAIN.x"));
  EXPECT_EQ(parseNodeId("s=a;b"), NodeId::str(0, "a;b"));
  for (const char* bad : {"", "85", "i=", "i=x", "ns=70000;i=1", "ns=1", "ns=;i=1", "s=", "ns=1;g=00000000-0000-0000-0000-000000000000", "i=1 "})
    EXPECT_FALSE(parseNodeId(bad)) << bad;
  EXPECT_EQ(formatNodeId(*parseNodeId("ns=4;s=|var|virtcom.Application.MAIN.x")), "ns=4;s=|var|virtcom.Application.MAIN.x");
}

TEST_F(OpcuaBridgeTest, ValuesCrossWithOneReadAndWritesOnlyWhatChanged) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config(wired()), bus_, report);
  ASSERT_NE(bridge, nullptr) << (report.problems.empty() ? "" : report.problems[0].text);
  EXPECT_EQ(report.found, (std::vector<bool>{true, true}));

  bus_.setReal(position_, 41.6);  // rounded into the INT
  ASSERT_TRUE(bridge->pull(bus_, 0)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(program_), 1234);
  const uint64_t before = bridge->requests();
  bridge->push(bus_, 0);
  EXPECT_EQ(bridge->requests(), before + 1) << "one Write";
  EXPECT_EQ(scan(), 1u);
  EXPECT_EQ(int16At(40), 42);

  // Unchanged: one Read, no Write.
  setInt16(32, -7);
  publish();
  ASSERT_TRUE(bridge->pull(bus_, 1'000'000));
  EXPECT_EQ(bus_.getInt(program_), -7);
  bridge->push(bus_, 1'000'000);
  EXPECT_EQ(bridge->requests(), before + 2) << "one Read, and no Write of an unchanged output";
  EXPECT_EQ(scan(), 0u);

  bus_.setReal(position_, -3.0);
  ASSERT_TRUE(bridge->pull(bus_, 2'000'000));
  bridge->push(bus_, 2'000'000);
  EXPECT_EQ(scan(), 1u);
  EXPECT_EQ(int16At(40), -3);
  EXPECT_EQ(server_->connectionCount(), 1u);
}

TEST_F(OpcuaBridgeTest, PollsEveryPollIntervalOnly) {
  ClientBridge::StartReport report;
  auto c = config(wired());
  c.pollNs = 10'000'000;
  auto bridge = ClientBridge::start(c, bus_, report);
  ASSERT_NE(bridge, nullptr);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  bridge->push(bus_, 0);
  const uint64_t after = bridge->requests();
  for (int64_t t = 1'000'000; t < 10'000'000; t += 1'000'000) {
    ASSERT_TRUE(bridge->pull(bus_, t));
    bridge->push(bus_, t);
  }
  EXPECT_EQ(bridge->requests(), after) << "nothing between two polls";
  ASSERT_TRUE(bridge->pull(bus_, 10'000'000));
  EXPECT_EQ(bridge->requests(), after + 1);
}

TEST_F(OpcuaBridgeTest, ARefusedConnectionIsReportedAtStart) {
  auto c = config(wired());
  server_->stop();
  server_.reset();
  ClientBridge::StartReport report;
  EXPECT_EQ(ClientBridge::start(c, bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].signal, ClientBridge::kNoSignal);
  EXPECT_EQ(report.problems[0].kind, Problem::Kind::Link);
  EXPECT_NE(report.problems[0].text.find("opcua: cannot connect to the OPC UA server at opc.tcp://127.0.0.1:"), std::string::npos)
      << report.problems[0].text;
  EXPECT_NE(report.problems[0].text.find("Connection refused"), std::string::npos) << report.problems[0].text;
}

TEST_F(OpcuaBridgeTest, EveryBadNodeIsReportedAtStartInOnePass) {
  TagId flag = bus_.add("Clamp.closed", ElemType::Bool);
  std::vector<BridgeSignal> signals = {
      {"ns=4;x=1", "ns=4;x=1", "Clamp.programNumber", program_, false, false},
  };
  ClientBridge::StartReport report;
  EXPECT_EQ(ClientBridge::start(config(signals), bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].text, "opcua: 'ns=4;x=1' is not a node id or a browse path (expected e.g. ns=4;s=NAME, ns=2;i=17 or /4:MAIN/4:x)");

  signals = {
      {node("MAIN.nothing"), "MAIN.nothing", "Clamp.programNumber", program_, false, false},
      {node("MAIN.serial"), "MAIN.serial", "Clamp.position", position_, true, false},  // read-only
      {node("MAIN.count"), "MAIN.count", "Clamp.closed", flag, false, false},           // INT to BOOL
      {node("MAIN.maybe"), "MAIN.maybe", "Clamp.other", program_, false, true},          // optional: skipped
  };
  report = {};
  EXPECT_EQ(ClientBridge::start(config(signals), bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 3u);
  EXPECT_EQ(report.problems[0].signal, 0u);
  EXPECT_EQ(report.problems[0].kind, Problem::Kind::Unknown);
  EXPECT_EQ(report.problems[0].text, "opcua: the server has no node 'MAIN.nothing' (" + node("MAIN.nothing") + ") to wire to Clamp.programNumber");
  EXPECT_EQ(report.problems[1].signal, 1u);
  EXPECT_NE(report.problems[1].text.find("'MAIN.serial' (" + node("MAIN.serial") + ") is not writable for this session"), std::string::npos)
      << report.problems[1].text;
  EXPECT_EQ(report.problems[2].signal, 2u);
  EXPECT_EQ(report.problems[2].text, "opcua: 'MAIN.count' (" + node("MAIN.count") + ") is Int16 on the server but input 'Clamp.closed' is BOOL");
  EXPECT_EQ(report.found, (std::vector<bool>{false, true, true, false}));
}

TEST_F(OpcuaBridgeTest, AnAnonymousSessionMayNotWriteByDefault) {
  server_->stop();
  startServer(ServerConfig{});  // anonymous read-only, the default
  ClientBridge::StartReport report;
  EXPECT_EQ(ClientBridge::start(config(wired()), bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].signal, 1u);
  EXPECT_NE(report.problems[0].text.find("--opcua-anonymous write"), std::string::npos) << report.problems[0].text;
  // Only reading: fine.
  report = {};
  auto readOnly = wired();
  readOnly.pop_back();
  EXPECT_NE(ClientBridge::start(config(readOnly), bus_, report), nullptr);
}

TEST_F(OpcuaBridgeTest, UsersLogOnWithTheirPassword) {
  server_->stop();
  ServerConfig c;
  c.users.push_back(makeUserAccount("op", UserAccess::Write, "op-pass", 1000));
  c.anonymous = UserAccess::None;
  startServer(c);
  ClientBridge::StartReport report;
  auto anonymous = config(wired());
  EXPECT_EQ(ClientBridge::start(anonymous, bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_NE(report.problems[0].text.find("the server refused an anonymous session: BadIdentityTokenInvalid"), std::string::npos)
      << report.problems[0].text;

  auto wrong = config(wired());
  wrong.client.timeoutNs = 10'000'000'000;  // the server hashes the password (PBKDF2) before it answers
  wrong.client.user = "op";
  wrong.client.password = "nope";
  report = {};
  EXPECT_EQ(ClientBridge::start(wrong, bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_NE(report.problems[0].text.find("the server refused user 'op': BadUserAccessDenied"), std::string::npos) << report.problems[0].text;

  auto right = wrong;
  right.client.password = "op-pass";
  report = {};
  auto bridge = ClientBridge::start(right, bus_, report);
  ASSERT_NE(bridge, nullptr) << report.problems[0].text;
  bus_.setReal(position_, 9);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  bridge->push(bus_, 0);
  EXPECT_EQ(scan(), 1u);
  EXPECT_EQ(int16At(40), 9);
}

TEST_F(OpcuaBridgeTest, ALostLinkFailsTheRunWithFaultOnLoss) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config(wired()), bus_, report);
  ASSERT_NE(bridge, nullptr);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  server_->stop();
  server_.reset();
  EXPECT_FALSE(bridge->pull(bus_, 1'000'000));
  EXPECT_NE(bridge->failure().find("opcua: link to the OPC UA server at opc.tcp://127.0.0.1:"), std::string::npos) << bridge->failure();
  EXPECT_NE(bridge->failure().find(" lost: reading the PLC's outputs: "), std::string::npos) << bridge->failure();
}

TEST_F(OpcuaBridgeTest, ALostLinkIsHeldAndReconnectedWithHold) {
  auto c = config(wired());
  c.faultOnLoss = false;
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(c, bus_, report);
  ASSERT_NE(bridge, nullptr);
  bus_.setReal(position_, 5);
  ASSERT_TRUE(bridge->pull(bus_, 0));
  bridge->push(bus_, 0);
  EXPECT_EQ(scan(), 1u);
  const uint16_t port = server_->endpoint().port;
  server_->stop();
  server_.reset();
  EXPECT_TRUE(bridge->pull(bus_, 1'000'000)) << "hold: the run goes on";
  EXPECT_TRUE(bridge->pull(bus_, 2'000'000));
  EXPECT_EQ(bus_.getInt(program_), 1234) << "the last command is held";
  ASSERT_EQ(reports_.size(), 1u) << "reported once";
  EXPECT_NE(reports_[0].find("(holding the last commands, retrying every poll)"), std::string::npos) << reports_[0];

  // The server is back on the same port: the bridge reconnects and rewrites every output.
  image_.assign(64, 0);
  setInt16(32, 77);
  restartServer(port, UserAccess::Write);
  ASSERT_TRUE(bridge->pull(bus_, 3'000'000)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(program_), 77);
  bridge->push(bus_, 3'000'000);
  EXPECT_EQ(scan(), 1u) << "the unchanged output is written again after reconnecting";
  EXPECT_EQ(int16At(40), 5);
  ASSERT_EQ(reports_.size(), 2u);
  EXPECT_NE(reports_[1].find("opcua: reconnected to the OPC UA server at"), std::string::npos) << reports_[1];
}

TEST_F(OpcuaBridgeTest, AServerBackWithoutTheWiringAsAtStartFailsTheRun) {
  auto c = config(wired());
  c.faultOnLoss = false;
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(c, bus_, report);
  ASSERT_NE(bridge, nullptr);
  const uint16_t port = server_->endpoint().port;
  server_->stop();
  server_.reset();
  EXPECT_TRUE(bridge->pull(bus_, 1'000'000)) << "hold: the run goes on";
  // Back, but anonymous sessions may no longer write: Clamp.position cannot reach the PLC.
  restartServer(port, UserAccess::Read);
  EXPECT_FALSE(bridge->pull(bus_, 2'000'000));
  EXPECT_NE(bridge->failure().find("opcua: the OPC UA server at opc.tcp://127.0.0.1:"), std::string::npos) << bridge->failure();
  EXPECT_NE(bridge->failure().find(" no longer matches the cell after reconnecting: opcua: 'MAIN.p.x' "), std::string::npos)
      << bridge->failure();
  EXPECT_NE(bridge->failure().find("is not writable for this session"), std::string::npos) << bridge->failure();
}

// MAIN.count is a variable of the folder MAIN; MAIN.p.x a component of the struct MAIN.p.
std::vector<BridgeSignal> OpcuaBridgeTest::wiredByPath() {
  return {{"/4:MAIN/4:count", "MAIN.count", "Clamp.programNumber", program_, false, false},
          {"/4:MAIN/4:p.4:x", "MAIN.p.x", "Clamp.position", position_, true, false}};
}

TEST_F(OpcuaBridgeTest, SignalsNamedByBrowsePathCrossAsByNodeId) {
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(config(wiredByPath()), bus_, report);
  ASSERT_NE(bridge, nullptr) << report.problems[0].text;
  ASSERT_TRUE(bridge->pull(bus_, 0)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(program_), 1234);
  bus_.setReal(position_, 7);
  bridge->push(bus_, 0);
  EXPECT_EQ(scan(), 1u);
  EXPECT_EQ(int16At(40), 7);
}

TEST_F(OpcuaBridgeTest, EveryBrowsePathLeadingNowhereIsReportedAtStartInOnePass) {
  std::vector<BridgeSignal> signals = {
      {"/4:MAIN/4:", "MAIN.x", "Clamp.programNumber", program_, false, false},
  };
  ClientBridge::StartReport report;
  EXPECT_EQ(ClientBridge::start(config(signals), bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].text, "opcua: the browse path '/4:MAIN/4:' at character 11: a browse name is missing "
                                     "(expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)");

  signals = {
      {"/4:MAIN/4:nothing", "MAIN.nothing", "Clamp.programNumber", program_, false, false},
      {"/4:MAIN/4:count", "MAIN.count", "Clamp.other", program_, false, false},
      {"/MAIN/count", "MAIN.count", "Clamp.position", position_, true, false},   // namespace 0: no match
      {"/4:MAIN/4:maybe", "MAIN.maybe", "Clamp.other", program_, false, true},  // optional: skipped
  };
  report = {};
  EXPECT_EQ(ClientBridge::start(config(signals), bus_, report), nullptr);
  ASSERT_EQ(report.problems.size(), 2u);
  EXPECT_EQ(report.problems[0].signal, 0u);
  EXPECT_EQ(report.problems[0].kind, Problem::Kind::Unknown);
  EXPECT_EQ(report.problems[0].text,
            "opcua: the browse path '/4:MAIN/4:nothing' of 'MAIN.nothing' leads to no node on the server: BadNoMatch (to wire to Clamp.programNumber)");
  EXPECT_EQ(report.problems[1].signal, 2u);
  EXPECT_EQ(report.problems[1].text,
            "opcua: the browse path '/MAIN/count' of 'MAIN.count' leads to no node on the server: BadNoMatch (to wire to Clamp.position)");
  EXPECT_EQ(report.found, (std::vector<bool>{false, true, false, false}));
}

TEST_F(OpcuaBridgeTest, BrowsePathsAreResolvedAgainAfterReconnecting) {
  auto c = config(wiredByPath());
  c.faultOnLoss = false;
  ClientBridge::StartReport report;
  auto bridge = ClientBridge::start(c, bus_, report);
  ASSERT_NE(bridge, nullptr) << report.problems[0].text;
  const uint16_t port = server_->endpoint().port;
  server_->stop();
  server_.reset();
  EXPECT_TRUE(bridge->pull(bus_, 1'000'000)) << "hold: the run goes on";
  // The restarted PLC names its variables ns=4;s=|var|plc2.Application...: the node ids found
  // at start are gone, the browse paths lead to the new ones.
  setInt16(32, 55);
  restartServer(port, UserAccess::Write, "plc2");
  ASSERT_TRUE(bridge->pull(bus_, 2'000'000)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(program_), 55);
  bus_.setReal(position_, 9);
  bridge->push(bus_, 2'000'000);
  EXPECT_EQ(scan(), 1u);
  EXPECT_EQ(int16At(40), 9);
}

class OpcuaBridgeSubscriptionTest : public OpcuaBridgeTest {
 protected:
  // A bridge of wired() that subscribes, polling every `pollNs`; null (and a failure) if it did not start.
  std::unique_ptr<ClientBridge> startSubscribing(int64_t pollNs) {
    auto c = config(wired());
    c.subscribe = true;
    c.pollNs = pollNs;
    ClientBridge::StartReport report;
    auto bridge = ClientBridge::start(c, bus_, report);
    EXPECT_NE(bridge, nullptr) << (report.problems.empty() ? "" : report.problems[0].text);
    return bridge;
  }
};

// Polls (as the simulation would) until `condition` holds or the deadline passes; false then,
// or if a poll failed.
template <class Condition>
bool pollUntil(ClientBridge& bridge, TagBus& bus, Condition condition) {
  int64_t now = 0;
  bool ok = true;
  return test::eventually([&] {
           ok = ok && bridge.pull(bus, now);
           bridge.push(bus, now);
           now += 1'000'000;
           return !ok || condition();
         }) &&
         ok;
}

TEST_F(OpcuaBridgeSubscriptionTest, ThePlcsOutputsArriveWithPublishResponses) {
  auto bridge = startSubscribing(10'000'000);
  ASSERT_NE(bridge, nullptr);
  EXPECT_TRUE(bridge->subscribed());
  EXPECT_EQ(bridge->updatesText(), "subscribed, published every 10 ms");
  // The first notification brings the value the item had when it was created.
  EXPECT_TRUE(pollUntil(*bridge, bus_, [&] { return bus_.getInt(program_) == 1234; })) << bridge->failure();
  setInt16(32, -7);
  publish();
  EXPECT_TRUE(pollUntil(*bridge, bus_, [&] { return bus_.getInt(program_) == -7; })) << bridge->failure();
  // Writes still cross, with the Publish posted meanwhile.
  bus_.setReal(position_, 12.0);
  EXPECT_TRUE(pollUntil(*bridge, bus_, [&] {
    scan();
    return int16At(40) == 12;
  })) << bridge->failure();
  EXPECT_EQ(int16At(40), 12);
  EXPECT_TRUE(reports_.empty());
}

TEST_F(OpcuaBridgeSubscriptionTest, AServerThatRefusesSubscriptionsIsRead) {
  ServerConfig sc;
  sc.anonymous = UserAccess::Write;
  sc.maxSubscriptions = 0;
  startServer(sc);
  auto bridge = startSubscribing(10'000'000);
  ASSERT_NE(bridge, nullptr);
  EXPECT_FALSE(bridge->subscribed());
  EXPECT_EQ(bridge->updatesText(), "a Read every 10 ms");
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_EQ(reports_[0], "opcua: " + bridge->peerText() +
                             " refused a subscription (BadTooManySubscriptions): its outputs are read every poll instead");
  ASSERT_TRUE(bridge->pull(bus_, 0)) << bridge->failure();
  EXPECT_EQ(bus_.getInt(program_), 1234);
}

TEST_F(OpcuaBridgeSubscriptionTest, AServerGoneIsALostLink) {
  auto bridge = startSubscribing(0);
  ASSERT_NE(bridge, nullptr);
  ASSERT_TRUE(bridge->subscribed());
  server_->stop();
  EXPECT_TRUE(test::eventually([&] { return !bridge->pull(bus_, 0); }));
  EXPECT_NE(bridge->failure().find(" lost: publishing: "), std::string::npos) << bridge->failure();
}

}  // namespace
}  // namespace virtcom::proto::opcua
