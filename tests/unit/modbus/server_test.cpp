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
  void startServer(std::vector<uint32_t> allow, size_t maxClients = ServerConfig().maxClients) {
    ServerConfig config;
    config.listen = {0x7f000001, 0};
    config.allowedPeers = std::move(allow);
    config.maxClients = maxClients;
    auto s = Server::start(config, {4, 4, 4});
    ASSERT_TRUE(s) << s.error();
    server_ = std::move(*s);
  }
  ImageView live() { return {inputs_, outputs_, memory_}; }

  std::array<uint8_t, 4> inputs_{}, outputs_{}, memory_{};
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
  startServer({0x0a000001});  // only 10.0.0.1
  LoopbackClient c(server_->endpoint().port);
  ASSERT_TRUE(c.connected());
  EXPECT_TRUE(c.closedByServer());
}

TEST_F(ServerTest, AClientBeyondMaxClientsIsDisconnectedAndTheOthersStayServed) {
  server_.reset();
  startServer({}, 1);
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
  auto allow = parseAllowList("127.0.0.1,10.0.0.2");
  ASSERT_TRUE(allow);
  EXPECT_EQ(*allow, (std::vector<uint32_t>{0x7f000001u, 0x0a000002u}));
  EXPECT_FALSE(parseAllowList("127.0.0.1,nope"));
  EXPECT_FALSE(parseAllowList(","));
}

}  // namespace
}  // namespace virtcom::proto::modbus
