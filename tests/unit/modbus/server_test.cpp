// The TCP server on loopback: writes wait for the scan thread, reads see the published snapshot,
// malformed frames and refused peers close only their own connection.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "proto/modbus/server.hpp"

namespace virtcom::proto::modbus {
namespace {

using Bytes = std::vector<uint8_t>;

// A blocking loopback client whose receives give up after 5 s (so a bug fails, never hangs).
class Client {
 public:
  explicit Client(uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~Client() { ::close(fd_); }
  bool connected() const { return connected_; }
  void send(const Bytes& b) { ASSERT_EQ(::send(fd_, b.data(), b.size(), MSG_NOSIGNAL), static_cast<ssize_t>(b.size())); }
  // Reads exactly n bytes; fewer if the server closed or timed out.
  Bytes receive(size_t n) {
    Bytes out(n);
    size_t got = 0;
    while (got < n) {
      ssize_t r = ::recv(fd_, out.data() + got, n - got, 0);
      if (r <= 0) break;
      got += static_cast<size_t>(r);
    }
    out.resize(got);
    return out;
  }
  // True if the server closed the connection (recv returns 0 before the timeout).
  bool closedByServer() {
    uint8_t b;
    return ::recv(fd_, &b, 1, 0) == 0;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override { startServer({}); }
  void startServer(std::vector<uint32_t> allow) {
    ServerConfig config;
    config.listen = {0x7f000001, 0};
    config.allowedPeers = std::move(allow);
    auto s = Server::start(config, {4, 4, 4});
    ASSERT_TRUE(s) << s.error();
    server_ = std::move(*s);
  }
  ImageView live() { return {inputs_, outputs_, memory_}; }

  std::array<uint8_t, 4> inputs_{}, outputs_{}, memory_{};
  std::unique_ptr<Server> server_;
};

TEST_F(ServerTest, WritesReachThePlcOnlyWhenTheScanThreadAppliesThem) {
  Client c(server_->endpoint().port);
  ASSERT_TRUE(c.connected());
  c.send({0, 1, 0, 0, 0, 6, 1, 0x06, 0x04, 0x00, 0x12, 0x34});  // %MW0 := 16#1234
  EXPECT_EQ(c.receive(12), (Bytes{0, 1, 0, 0, 0, 6, 1, 0x06, 0x04, 0x00, 0x12, 0x34}));
  EXPECT_EQ(memory_[0], 0);
  // A scan ends before the write is applied: the client still reads back what it wrote.
  outputs_[0] = 0x55;
  server_->publishSnapshot(live());
  c.send({0, 2, 0, 0, 0, 6, 1, 0x03, 0x04, 0x00, 0x00, 0x01});
  EXPECT_EQ(c.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x03, 0x02, 0x12, 0x34}));
  EXPECT_EQ(server_->applyPendingWrites(live()), 2u);
  EXPECT_EQ(memory_[0], 0x34);
  EXPECT_EQ(memory_[1], 0x12);
  EXPECT_EQ(server_->applyPendingWrites(live()), 0u);
  c.send({0, 3, 0, 0, 0, 6, 1, 0x01, 0x00, 0x00, 0x00, 0x08});
  EXPECT_EQ(c.receive(10), (Bytes{0, 3, 0, 0, 0, 4, 1, 0x01, 0x01, 0x55}));
}

TEST_F(ServerTest, AMalformedFrameClosesOnlyThatConnection) {
  Client good(server_->endpoint().port), bad(server_->endpoint().port);
  bad.send({0, 1, 0, 7, 0, 6, 1, 0x03, 0, 0, 0, 1});  // protocol id 7
  EXPECT_TRUE(bad.closedByServer());
  good.send({0, 9, 0, 0, 0, 6, 0xFF, 0x03, 0x00, 0x05, 0x00, 0x01});  // %QW5 does not exist
  EXPECT_EQ(good.receive(9), (Bytes{0, 9, 0, 0, 0, 3, 0xFF, 0x83, 0x02}));
}

TEST_F(ServerTest, AFrameSplitAcrossSegmentsIsReassembled) {
  Client c(server_->endpoint().port);
  c.send({0, 1, 0, 0, 0});
  c.send({6, 1, 0x04, 0x00});
  c.send({0x00, 0x00, 0x02, 0, 2, 0, 0, 0, 6, 1, 0x04, 0, 0, 0, 1});
  EXPECT_EQ(c.receive(13), (Bytes{0, 1, 0, 0, 0, 7, 1, 0x04, 0x04, 0, 0, 0, 0}));
  EXPECT_EQ(c.receive(11), (Bytes{0, 2, 0, 0, 0, 5, 1, 0x04, 0x02, 0, 0}));
}

TEST_F(ServerTest, APeerNotOnTheAllowListIsDisconnected) {
  server_.reset();
  startServer({0x0a000001});  // only 10.0.0.1
  Client c(server_->endpoint().port);
  ASSERT_TRUE(c.connected());
  EXPECT_TRUE(c.closedByServer());
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
