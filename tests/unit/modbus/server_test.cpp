// The TCP server on loopback: writes wait for the scan thread, reads see the published snapshot,
// malformed frames and refused peers close only their own connection.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "proto/modbus/server.hpp"
#include "support/loopback_client.hpp"

namespace virtcom::proto::modbus {
namespace {

using Bytes = std::vector<uint8_t>;

using virtcom::test::LoopbackClient;

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override { startServer({}); }
  void startServer(std::vector<net::Ipv4Net> allow, net::PeerLimits limits = {}, bool readOnly = false) {
    ServerConfig config;
    config.listen = {0x7f000001, 0};
    config.peers = net::PeerPolicy(std::move(allow), limits, "modbus", "--modbus-allow");
    config.peers.setLog([this](const std::string& line) { refusals_.push_back(line); });
    config.readOnly = readOnly;
    auto s = Server::start(config, {4, 4, 4});
    ASSERT_TRUE(s) << s.error();
    server_ = std::move(*s);
  }
  ImageView live() { return {inputs_, outputs_, memory_}; }

  std::array<uint8_t, 4> inputs_{}, outputs_{}, memory_{};
  std::vector<std::string> refusals_;  // written by the I/O thread, read once it has refused
  std::unique_ptr<Server> server_;
};

TEST_F(ServerTest, WritesReachThePlcOnlyWhenTheScanThreadAppliesThem) {
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.connected());
  ASSERT_TRUE(c.send({0, 1, 0, 0, 0, 6, 1, 0x06, 0x04, 0x00, 0x12, 0x34}));  // %MW0 := 16#1234
  EXPECT_EQ(c.receive(12), (Bytes{0, 1, 0, 0, 0, 6, 1, 0x06, 0x04, 0x00, 0x12, 0x34}));
  EXPECT_EQ(memory_[0], 0);
  // A scan ends before the write is applied: the client still reads back what it wrote.
  outputs_[0] = 0x55;
  server_->publishSnapshot(live());
  ASSERT_TRUE(c.send({0, 2, 0, 0, 0, 6, 1, 0x03, 0x04, 0x00, 0x00, 0x01}));
  EXPECT_EQ(c.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x03, 0x02, 0x12, 0x34}));
  EXPECT_EQ(server_->applyPendingWrites(live()), 2u);
  EXPECT_EQ(memory_[0], 0x34);
  EXPECT_EQ(memory_[1], 0x12);
  EXPECT_EQ(server_->applyPendingWrites(live()), 0u);
  ASSERT_TRUE(c.send({0, 3, 0, 0, 0, 6, 1, 0x01, 0x00, 0x00, 0x00, 0x08}));
  EXPECT_EQ(c.receive(10), (Bytes{0, 3, 0, 0, 0, 4, 1, 0x01, 0x01, 0x55}));
}

TEST_F(ServerTest, AMalformedFrameClosesOnlyThatConnection) {
  LoopbackClient good(server_->endpoint().port), bad(server_->endpoint().port);
  ASSERT_TRUE(bad.send({0, 1, 0, 7, 0, 6, 1, 0x03, 0, 0, 0, 1}));  // protocol id 7
  EXPECT_TRUE(bad.closedByServer());
  ASSERT_TRUE(good.send({0, 9, 0, 0, 0, 6, 0xFF, 0x03, 0x00, 0x05, 0x00, 0x01}));  // %QW5 does not exist
  EXPECT_EQ(good.receive(9), (Bytes{0, 9, 0, 0, 0, 3, 0xFF, 0x83, 0x02}));
}

TEST_F(ServerTest, AFrameSplitAcrossSegmentsIsReassembled) {
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.send({0, 1, 0, 0, 0}));
  ASSERT_TRUE(c.send({6, 1, 0x04, 0x00}));
  ASSERT_TRUE(c.send({0x00, 0x00, 0x02, 0, 2, 0, 0, 0, 6, 1, 0x04, 0, 0, 0, 1}));
  EXPECT_EQ(c.receive(13), (Bytes{0, 1, 0, 0, 0, 7, 1, 0x04, 0x04, 0, 0, 0, 0}));
  EXPECT_EQ(c.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));
}

TEST_F(ServerTest, APeerNotOnTheAllowListIsDisconnected) {
  server_.reset();
  startServer({net::Ipv4Net{0x0a000000, 0xff000000}});  // only 10.0.0.0/8
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.connected());
  EXPECT_TRUE(c.closedByServer());
  server_->stop();
  EXPECT_EQ(refusals_, std::vector<std::string>{"modbus: refused 127.0.0.1: not in --modbus-allow"});
}

TEST_F(ServerTest, APeerInAnAllowedNetworkIsServed) {
  server_.reset();
  startServer({net::Ipv4Net{0x7f000000, 0xff000000}});  // 127.0.0.0/8
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.send({0, 1, 0, 0, 0, 6, 1, 0x04, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(c.receive(11), (Bytes{0, 1, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));
}

TEST_F(ServerTest, AReadOnlyServerRefusesWritesWithIllegalFunctionAndStillReads) {
  server_.reset();
  startServer({}, {}, true);
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.send({0, 1, 0, 0, 0, 6, 1, 0x06, 0x04, 0x00, 0x12, 0x34}));  // %MW0 := 16#1234
  EXPECT_EQ(c.receive(9), (Bytes{0, 1, 0, 0, 0, 3, 1, 0x86, 0x01}));
  ASSERT_TRUE(c.send({0, 2, 0, 0, 0, 6, 1, 0x03, 0x04, 0x00, 0x00, 0x01}));
  EXPECT_EQ(c.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x03, 0x02, 0, 0}));
  EXPECT_EQ(server_->applyPendingWrites(live()), 0u);
}

TEST_F(ServerTest, RequestsBeyondTheRateAreAnsweredBusy) {
  server_.reset();
  startServer({}, net::PeerLimits{.requestsPerSecond = 1});  // one request, then one a second
  LoopbackClient c(server_->endpoint().port);
  const Bytes read = {0, 1, 0, 0, 0, 6, 1, 0x04, 0x00, 0x00, 0x00, 0x01};
  Bytes two = read;
  two.insert(two.end(), read.begin(), read.end());
  ASSERT_TRUE(c.send(two));  // one segment: both answered in one pass, far less than a second apart
  EXPECT_EQ(c.receive(11), (Bytes{0, 1, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));
  EXPECT_EQ(c.receive(9), (Bytes{0, 1, 0, 0, 0, 3, 1, 0x84, 0x06}));
}

TEST_F(ServerTest, AClientBeyondThePerPeerLimitIsDisconnected) {
  server_.reset();
  startServer({}, net::PeerLimits{.maxPerPeer = 1});
  LoopbackClient first(server_->endpoint().port);
  ASSERT_TRUE(first.send({0, 1, 0, 0, 0, 6, 1, 0x04, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(first.receive(11), (Bytes{0, 1, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));  // accepted
  LoopbackClient second(server_->endpoint().port);
  EXPECT_TRUE(second.closedByServer());
  server_->stop();
  ASSERT_EQ(refusals_.size(), 1u);
  EXPECT_EQ(refusals_[0], "modbus: refused 127.0.0.1: this address has its 1 connections (--max-clients-per-peer)");
}

TEST_F(ServerTest, AClientBeyondMaxClientsIsDisconnectedAndTheOthersStayServed) {
  server_.reset();
  startServer({}, net::PeerLimits{.maxConnections = 1});
  LoopbackClient first(server_->endpoint().port);
  ASSERT_TRUE(first.send({0, 1, 0, 0, 0, 6, 1, 0x04, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(first.receive(11), (Bytes{0, 1, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));  // accepted
  LoopbackClient second(server_->endpoint().port);
  ASSERT_TRUE(second.connected());
  EXPECT_TRUE(second.closedByServer());
  ASSERT_TRUE(first.send({0, 2, 0, 0, 0, 6, 1, 0x04, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(first.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));
}

TEST(Endpoint, ParsesHostAndPort) {
  auto e = parseEndpoint("127.0.0.1:1502");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->ipv4, 0x7f000001u);
  EXPECT_EQ(e->port, 1502);
  EXPECT_EQ(formatEndpoint(*parseEndpoint("localhost:0")), "127.0.0.1:0");
  EXPECT_FALSE(parseEndpoint("127.0.0.1"));
  EXPECT_FALSE(parseEndpoint("127.0.0.1:70000"));
  EXPECT_FALSE(parseEndpoint("127.0.0.1:"));
  EXPECT_FALSE(parseEndpoint("example.com:502"));
  auto allow = virtcom::parseAllowList("127.0.0.1,10.0.0.0/8");
  ASSERT_TRUE(allow);
  EXPECT_EQ(*allow, (std::vector<net::Ipv4Net>{{0x7f000001u}, {0x0a000000u, 0xff000000u}}));
  EXPECT_FALSE(virtcom::parseAllowList("127.0.0.1,nope"));
  EXPECT_FALSE(virtcom::parseAllowList(","));
}

}  // namespace
}  // namespace virtcom::proto::modbus
