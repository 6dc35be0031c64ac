// End-to-end (issue 16): `virtcom exec --ads` as Beckhoff's AdsLib/adstool, pyads and ads-client
// meet it on a real TwinCAT: reads longer than the symbol, handles kept per AMS route across
// connections, bit-located globals, a %M area the program sizes, Tc2_System types, the UDP
// discovery service, and the first sample of a notification. Driven by an AdsLib-style client
// (adslib_style_client.hpp), a raw UDP client and the npm ads-client (tests/e2e/ads).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "adslib_style_client.hpp"
#include "server_process.hpp"
#include "shell_command.hpp"

namespace {

using Bytes = std::vector<uint8_t>;
using virtcom::e2e::AdsLibStyleClient;
using virtcom::e2e::ServerProcess;

const std::string kExe = VIRTCOM_EXE;
const std::string kDataDir = VIRTCOM_E2E_DATA;
const std::string kClientDir = VIRTCOM_ADS_CLIENT_DIR;
const std::string kTc2System = std::string(VIRTCOM_SOURCE_DIR) + "/lib/tc2_system.st";

std::vector<std::string> programArgs() { return {"exec", kTc2System, "ads_twincat/MAIN.st"}; }

std::unique_ptr<ServerProcess> startServer(std::vector<std::string> extra = {"--ads-discovery", "off"}) {
  std::vector<std::string> args = programArgs();
  for (const char* a : {"--ads", "127.0.0.1:0", "--ads-netid", "10.20.30.40.1.1"}) args.push_back(a);
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<ServerProcess>(kExe, args, kDataDir, "ads: serving on ");
}

// A STRING's characters: up to its NUL.
std::string text(const Bytes& b) {
  std::string s(b.begin(), b.end());
  return s.substr(0, s.find('\0'));
}

TEST(AdsTwinCatE2e, ReadsLongerThanTheSymbolAnswerTheSymbol) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  AdsLibStyleClient c(server->port());
  // pyads: a handle, then the value by handle with a 1024-byte buffer.
  auto h = c.handle("MAIN.message");
  ASSERT_TRUE(h);
  auto r = c.read(0xF005, *h, 1024);
  EXPECT_EQ(r.result, 0u);
  EXPECT_EQ(r.data.size(), 256u);  // T_MaxString: STRING(255)
  EXPECT_EQ(text(r.data), "hello from virtcom");
  // adstool var --type=STRING: by name (0xF004) with a large buffer.
  std::string name = "MAIN.message";
  r = c.readWrite(0xF004, 0, 4096, Bytes(name.begin(), name.end()));
  EXPECT_EQ(r.result, 0u);
  EXPECT_EQ(r.data.size(), 256u);
  EXPECT_EQ(c.release(*h), 0u);
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(AdsTwinCatE2e, HandlesLiveOnTheAmsRouteAcrossConnections) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  uint32_t handle = 0;
  {
    AdsLibStyleClient first(server->port());  // adstool, first process: creates the handle
    auto h = first.handle("MAIN.maxLevel");
    ASSERT_TRUE(h);
    handle = *h;
  }
  AdsLibStyleClient next(server->port());  // the next process: same AMS port 30000
  auto r = next.read(0xF005, handle, 2);
  EXPECT_EQ(r.result, 0u);
  EXPECT_EQ(r.data, (Bytes{100, 0}));
  AdsLibStyleClient other(server->port(), 30001);  // another AMS port: not its handle
  EXPECT_EQ(other.read(0xF005, handle, 2).result, 0x710u);
  EXPECT_EQ(next.release(handle), 0u);
  EXPECT_EQ(next.read(0xF005, handle, 2).result, 0x710u);
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(AdsTwinCatE2e, BitGlobalsAndTheMemoryAreaTheProgramDeclares) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  AdsLibStyleClient c(server->port());
  auto lamp = c.handle("gLamp");
  ASSERT_TRUE(lamp);
  EXPECT_TRUE(virtcom::test::eventually([&] { return c.read(0xF005, *lamp, 1).data == Bytes{1}; }));
  EXPECT_EQ(c.read(0xF031, 15, 1).data, Bytes{1});  // %QX1.7
  ASSERT_TRUE(c.handle("gStart"));
  auto size = c.read(0x4025, 0, 4);
  ASSERT_EQ(size.data.size(), 4u);
  EXPECT_GE(AdsLibStyleClient::get32(size.data, 0), 1028u);
  EXPECT_TRUE(virtcom::test::eventually([&] { return c.read(0x4020, 1027, 1).data == Bytes{0x5A}; }));
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  // exec --print reaches them by name too.
  std::string command = "cd '" + kDataDir + "' && '" + kExe + "' exec '" + kTc2System +
                        "' ads_twincat/MAIN.st --cycles 2 --print gLamp --print gStart";
  std::string output;
  EXPECT_EQ(virtcom::e2e::shell(command, output), 0) << output;
  EXPECT_NE(output.find("gLamp = TRUE"), std::string::npos) << output;
  EXPECT_NE(output.find("gStart = FALSE"), std::string::npos) << output;
}

// AdsLib registers its callback only once the AddDeviceNotification reply is in; the first
// sample must come after it. MAIN.maxLevel never changes: the first sample is the only one.
TEST(AdsTwinCatE2e, AdsLibReceivesTheFirstSample) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  AdsLibStyleClient c(server->port());
  auto h = c.handle("MAIN.maxLevel");
  ASSERT_TRUE(h);
  ASSERT_TRUE(c.notifyByHandle(*h, 2));
  auto sample = c.nextSample();
  ASSERT_TRUE(sample) << "no sample after the reply; lost with it: " << c.lostSamples();
  EXPECT_EQ(*sample, (Bytes{100, 0}));
  EXPECT_EQ(c.lostSamples(), 0u);
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

// A UDP exchange with the discovery service: the reply datagram, empty on timeout.
Bytes udpExchange(uint16_t port, const Bytes& request) {
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  timeval timeout{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(fd, request.data(), request.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  Bytes reply(2048);
  ssize_t n = ::recv(fd, reply.data(), reply.size(), 0);
  ::close(fd);
  reply.resize(n > 0 ? static_cast<size_t>(n) : 0);
  return reply;
}

// The request head AdsLib and pyads send: cookie, invoke id, service, AMS address, tag count.
Bytes discoveryRequest(uint32_t service, uint32_t tags) {
  Bytes r = AdsLibStyleClient::u32s({0x71146603, 0, service});
  for (uint8_t b : {192, 168, 1, 50, 1, 1, 0x10, 0x27}) r.push_back(b);
  Bytes count = AdsLibStyleClient::u32s({tags});
  r.insert(r.end(), count.begin(), count.end());
  return r;
}

void tag(Bytes& r, uint16_t id, const Bytes& data) {
  r.push_back(static_cast<uint8_t>(id));
  r.push_back(0);
  r.push_back(static_cast<uint8_t>(data.size()));
  r.push_back(0);
  r.insert(r.end(), data.begin(), data.end());
}

TEST(AdsTwinCatE2e, UdpDiscoveryIdentifiesAndAddsRoutes) {
  auto server = startServer({"--ads-discovery", "0", "--ads-route-password", "1"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  const std::string prefix = "ads: discovery on UDP 127.0.0.1:";
  const size_t at = server->errorOutput().find(prefix);
  ASSERT_NE(at, std::string::npos) << server->errorOutput();
  const auto udpPort = static_cast<uint16_t>(std::stoi(server->errorOutput().substr(at + prefix.size())));

  // Identify (adstool HOST netid; pyads adsGetNetIdForPLC reads the NetId at bytes 12..17).
  Bytes reply = udpExchange(udpPort, discoveryRequest(1, 0));
  ASSERT_GE(reply.size(), 24u);
  EXPECT_EQ(AdsLibStyleClient::get32(reply, 0), 0x71146603u);
  EXPECT_EQ(AdsLibStyleClient::get32(reply, 8), 0x80000001u);
  EXPECT_EQ(Bytes(reply.begin() + 12, reply.begin() + 18), (Bytes{10, 20, 30, 40, 1, 1}));

  // Add route as pyads add_route_to_plc sends it: route name, NetId, user, password, host.
  auto addRoute = [](uint8_t password) {
    Bytes add = discoveryRequest(6, 5);
    tag(add, 12, {'p', 'c', 0});
    tag(add, 7, {192, 168, 1, 50, 1, 1});
    tag(add, 13, {'A', 'd', 'm', 'i', 'n', 'i', 's', 't', 'r', 'a', 't', 'o', 'r', 0});
    tag(add, 2, {password, 0});
    tag(add, 5, {'1', '9', '2', '.', '1', '6', '8', '.', '1', '.', '5', '0', 0});
    return add;
  };
  reply = udpExchange(udpPort, addRoute('1'));
  ASSERT_EQ(reply.size(), 32u);  // pyads reads 32 bytes
  EXPECT_EQ(reply[11], 0x80);    // pyads: a reply
  EXPECT_EQ(Bytes(reply.begin() + 26, reply.begin() + 29), (Bytes{4, 0, 0}));  // pyads: accepted
  EXPECT_EQ(AdsLibStyleClient::get32(reply, 28), 0u);                          // AdsLib: status 0

  // The wrong password: refused with 0x704 and logged (docs/security.md).
  reply = udpExchange(udpPort, addRoute('2'));
  ASSERT_EQ(reply.size(), 32u);
  EXPECT_EQ(AdsLibStyleClient::get32(reply, 28), 0x704u);
  EXPECT_TRUE(server->waitFor("ads: refused 127.0.0.1: wrong or no credentials")) << server->errorOutput();
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(AdsTwinCatE2e, NpmAdsClientScenario) {
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/ads-client"))
      << "the npm ads-client is missing: run `npm ci --prefix tests/e2e/ads` (make test does)";
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  std::string output;
  EXPECT_EQ(virtcom::e2e::shell("cd '" + kClientDir + "' && node check_twincat_fidelity.js " + std::to_string(server->port()), output), 0)
      << output;
  EXPECT_NE(output.find("ads-client fidelity checks passed"), std::string::npos) << output;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

}  // namespace
