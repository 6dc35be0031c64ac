// The ADS server on loopback: reads see the published snapshot, writes wait for the scan
// thread (and reach the input image for %I), a publish wakes on-change notifications at once,
// a malformed frame or a refused peer closes only its own connection.
#include "proto/ads/server.hpp"

#include <gtest/gtest.h>

#include "ads_test_support.hpp"
#include "support/loopback_client.hpp"

namespace virtcom::proto::ads {
namespace {

using namespace testing;

using virtcom::test::LoopbackClient;

// The ADS data of the next frame (after its 38 header bytes); empty on close or timeout.
Bytes nextData(LoopbackClient& c) {
  Bytes head = c.receive(kFrameHeaderSize);
  if (head.size() < kFrameHeaderSize) return {};
  return c.receive(head[26] | head[27] << 8 | head[28] << 16 | head[29] << 24);
}

// Sends one datagram to the loopback UDP `port` and returns the reply (empty after 5 s).
Bytes udpExchange(uint16_t port, const Bytes& request) {
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  timeval timeout{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(fd, request.data(), request.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  Bytes reply(512);
  ssize_t n = ::recv(fd, reply.data(), reply.size(), 0);
  ::close(fd);
  reply.resize(n > 0 ? static_cast<size_t>(n) : 0);
  return reply;
}

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ServerConfig config;
    config.listen.port = 0;
    auto s = Server::start(config, table);
    ASSERT_TRUE(s) << s.error();
    server = std::move(*s);
    image[32] = 42;
    server->publishSnapshot(image, kAdsStateRun);
  }
  SymbolTable table = makeTable();
  std::unique_ptr<Server> server;
  Bytes image = Bytes(64, 0), inputImage = Bytes(4, 0);
};

TEST_F(ServerTest, ReadsTheSnapshotAndQueuesWrites) {
  LoopbackClient c(server->endpoint().port);
  ASSERT_TRUE(c.connected());
  ASSERT_TRUE(c.send(amsRequest(kPlcPort, 2, u32s({0x4040, 32, 2}))));
  EXPECT_EQ(hex(nextData(c)), "00 00 00 00 02 00 00 00 2a 00");
  ASSERT_TRUE(c.send(amsRequest(kPlcPort, 3, u32s({0xF020, 1, 2}, {7, 8}))));
  EXPECT_EQ(hex(nextData(c)), "00 00 00 00");
  EXPECT_EQ(image[17], 0);  // not before the scan thread takes it
  EXPECT_EQ(server->applyPendingWrites({image, inputImage}), 1u);
  EXPECT_EQ(image[17], 7);
  EXPECT_EQ(image[18], 8);
  EXPECT_EQ(hex(inputImage), "00 07 08 00");
  EXPECT_EQ(server->applyPendingWrites({image, inputImage}), 0u);
}

TEST_F(ServerTest, PublishWakesOnChangeNotifications) {
  LoopbackClient c(server->endpoint().port);
  for (uint8_t value = 43; value < 53; ++value) {
    ASSERT_TRUE(c.send(amsRequest(kPlcPort, 6, u32s({0x4040, 32, 1, 4, 0, 0, 0, 0, 0, 0}))));
    Bytes reply = nextData(c);
    ASSERT_EQ(reply.size(), 8u);
    EXPECT_EQ(reply[0], 0);
    Bytes initial = nextData(c);
    ASSERT_EQ(initial.size(), 29u);
    EXPECT_EQ(initial[28], value - 1);
    image[32] = value;
    server->publishSnapshot(image, kAdsStateRun);  // at once: no polling interval to wait for
    Bytes change = nextData(c);
    ASSERT_EQ(change.size(), 29u) << "no notification after publish " << int(value);
    EXPECT_EQ(change[28], value);
    ASSERT_TRUE(c.send(amsRequest(kPlcPort, 7, u32s({reply[4] | reply[5] << 8u}))));
    EXPECT_EQ(hex(nextData(c)), "00 00 00 00");
  }
}

TEST_F(ServerTest, MalformedFrameClosesOnlyItsConnection) {
  LoopbackClient good(server->endpoint().port), bad(server->endpoint().port);
  ASSERT_TRUE(bad.send({0x00, 0x00, 0x05, 0x00, 0x00, 0x00}));  // shorter than an AMS header
  EXPECT_TRUE(bad.closedByServer());
  ASSERT_TRUE(good.send(amsRequest(kPlcPort, 4, {})));
  EXPECT_EQ(hex(nextData(good)), "00 00 00 00 05 00 00 00");
}

TEST(AdsServerAllowList, RefusedPeerIsClosed) {
  SymbolTable table = makeTable();
  ServerConfig config;
  config.listen.port = 0;
  config.peers = net::PeerPolicy({net::Ipv4Net{0x0a000001}}, {}, "ads", "--ads-allow");  // 10.0.0.1: not loopback
  auto server = Server::start(config, table);
  ASSERT_TRUE(server);
  LoopbackClient c((*server)->endpoint().port);
  EXPECT_TRUE(c.closedByServer());
}

// The route table grows as on TwinCAT: an add route with the password lets its NetId and the
// sender's address in (docs/security.md, ADS routes).
TEST(AdsServerRoutes, AnAddRouteWithThePasswordLetsItsNetIdAndAddressIn) {
  SymbolTable table = makeTable();
  ServerConfig config;
  config.listen.port = 0;
  config.discoveryPort = 0;
  config.peers = net::PeerPolicy({net::Ipv4Net{0x0a000001}}, {}, "ads", "--ads-allow");
  config.peers.setLog([](const std::string&) {});
  config.allowedNetIds = {{1, 2, 3, 4, 1, 1}};
  config.routePassword = "pw";
  auto server = Server::start(config, table);
  ASSERT_TRUE(server) << server.error();
  (*server)->publishSnapshot(Bytes(64, 0), kAdsStateRun);
  {
    LoopbackClient before((*server)->endpoint().port);
    EXPECT_TRUE(before.closedByServer());
  }
  // Add route: NetId tag = the test client's NetId, password tag "pw".
  Bytes add = u32s({0x71146603, 1, 6, 0, 0, 2});
  const Bytes netIdTag = {0x07, 0, 6, 0}, passwordTag = {0x02, 0, 3, 0, 'p', 'w', 0};
  add.insert(add.end(), netIdTag.begin(), netIdTag.end());
  add.insert(add.end(), kClientNetId.begin(), kClientNetId.end());
  add.insert(add.end(), passwordTag.begin(), passwordTag.end());
  Bytes reply = udpExchange((*server)->discoveryEndpoint()->port, add);
  ASSERT_EQ(reply.size(), 32u);
  EXPECT_EQ(hex(Bytes(reply.end() - 4, reply.end())), "00 00 00 00");
  LoopbackClient after((*server)->endpoint().port);
  ASSERT_TRUE(after.send(amsRequest(kPlcPort, 4, {})));  // ReadState from kClientNetId
  EXPECT_EQ(hex(nextData(after)), "00 00 00 00 05 00 00 00");
}

TEST(AdsServerStart, BusyPortIsAnError) {
  SymbolTable table = makeTable();
  ServerConfig config;
  config.listen.port = 0;
  auto first = Server::start(config, table);
  ASSERT_TRUE(first);
  config.listen.port = (*first)->endpoint().port;
  auto second = Server::start(config, table);
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().find("cannot bind 127.0.0.1:"), std::string::npos) << second.error();
}

// UDP discovery next to AMS/TCP; a port already taken leaves the TCP server serving without it.
TEST(AdsServerStart, DiscoveryOnUdpOrABusyPortWithoutIt) {
  SymbolTable table = makeTable();
  ServerConfig config;
  config.listen.port = 0;
  config.discoveryPort = 0;
  auto first = Server::start(config, table);
  ASSERT_TRUE(first);
  auto udp = (*first)->discoveryEndpoint();
  ASSERT_TRUE(udp);
  Bytes reply = udpExchange(udp->port, u32s({0x71146603, 4, 1, 0, 0, 0}));
  ASSERT_GE(reply.size(), 20u);
  EXPECT_EQ(hex(Bytes(reply.begin(), reply.begin() + 20)), "03 66 14 71 04 00 00 00 01 00 00 80 7f 00 00 01 01 01 10 27");

  config.discoveryPort = udp->port;
  auto second = Server::start(config, table);
  ASSERT_TRUE(second);
  EXPECT_FALSE((*second)->discoveryEndpoint());
  EXPECT_NE((*second)->discoveryProblem().find("cannot bind UDP 127.0.0.1:"), std::string::npos) << (*second)->discoveryProblem();
  config.discoveryPort.reset();
  auto off = Server::start(config, table);
  ASSERT_TRUE(off);
  EXPECT_FALSE((*off)->discoveryEndpoint());
  EXPECT_TRUE((*off)->discoveryProblem().empty());
}

}  // namespace
}  // namespace virtcom::proto::ads
