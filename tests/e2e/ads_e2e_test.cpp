// End-to-end: `virtcom exec ads/GVL.st ads/MAIN.st --ads 127.0.0.1:0` in its own process, driven
// by the real npm ads-client (tests/e2e/ads, installed by `make test` with npm ci) and by raw AMS
// frames for what a well-behaved client never does: abrupt disconnects, garbage, half frames.
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "server_process.hpp"
#include "support/eventually.hpp"
#include "support/loopback_client.hpp"

namespace {

using Bytes = std::vector<uint8_t>;
using virtcom::e2e::ServerProcess;
using virtcom::test::eventually;
using virtcom::test::LoopbackClient;

const std::string kExe = VIRTCOM_EXE;
const std::string kDataDir = VIRTCOM_E2E_DATA;
const std::string kClientDir = VIRTCOM_ADS_CLIENT_DIR;

std::unique_ptr<ServerProcess> startServer(std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"exec", "ads/GVL.st", "ads/MAIN.st", "--ads", "127.0.0.1:0"};
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<ServerProcess>(kExe, args, kDataDir, "ads: serving on ");
}

void put32(Bytes& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint32_t get32(const Bytes& b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

// An AMS packet to 127.0.0.1.1.1:851 from 10.0.0.1.1.1:30000 (docs/ads.md, Wire reference:
// AMS/TCP and the AMS header).
Bytes amsPacket(uint16_t command, const Bytes& data, uint32_t invokeId = 1) {
  Bytes f{0, 0};
  put32(f, static_cast<uint32_t>(32 + data.size()));
  for (uint8_t b : {127, 0, 0, 1, 1, 1, 0x53, 0x03, 10, 0, 0, 1, 1, 1, 0x30, 0x75}) f.push_back(b);
  f.push_back(static_cast<uint8_t>(command));
  f.push_back(0);
  f.push_back(4);
  f.push_back(0);
  put32(f, static_cast<uint32_t>(data.size()));
  put32(f, 0);
  put32(f, invokeId);
  f.insert(f.end(), data.begin(), data.end());
  return f;
}

// ReadWrite (command 9) of `ig` with a NUL-terminated name.
Bytes byName(uint32_t ig, const std::string& name, uint32_t readLength) {
  Bytes d;
  put32(d, ig);
  put32(d, 0);
  put32(d, readLength);
  put32(d, static_cast<uint32_t>(name.size() + 1));
  d.insert(d.end(), name.begin(), name.end());
  d.push_back(0);
  return amsPacket(9, d);
}

// One whole AMS/TCP frame; empty if the server closed or timed out.
Bytes frame(LoopbackClient& c) {
  Bytes head = c.receive(6);
  if (head.size() < 6) return {};
  Bytes rest = c.receive(get32(head, 2));
  head.insert(head.end(), rest.begin(), rest.end());
  return head;
}

// The result field (first u32 of the ADS data) of a response frame.
uint32_t adsResult(const Bytes& frame) { return frame.size() >= 42 ? get32(frame, 38) : 0xFFFFFFFF; }

// MAIN.ticks read by name (0xF004): the scans so far.
uint32_t ticks(LoopbackClient& c) {
  EXPECT_TRUE(c.send(byName(0xF004, "MAIN.ticks", 4)));
  Bytes r = frame(c);
  EXPECT_EQ(adsResult(r), 0u);
  return r.size() >= 50 ? get32(r, 46) : 0;
}

TEST(AdsE2e, NpmAdsClientScenario) {
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/ads-client"))
      << "the npm ads-client is missing: run `npm ci --prefix tests/e2e/ads` (make test does)";
  auto server = startServer({"--audit-writes", "each"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  std::string command = "cd '" + kClientDir + "' && node check_ads_client.js " + std::to_string(server->port()) + " 2>&1";
  FILE* node = ::popen(command.c_str(), "r");
  ASSERT_NE(node, nullptr);
  std::string output;
  std::array<char, 512> buf;
  while (size_t n = std::fread(buf.data(), 1, buf.size(), node)) output.append(buf.data(), n);
  int status = ::pclose(node);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("ads-client checks passed"), std::string::npos) << output;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  // Every accepted write audited with the client's address and AmsNetId (docs/security.md);
  // the refused ones (ads_readonly, CONSTANT) are not writes.
  const std::string log = server->errorOutput();
  EXPECT_NE(log.find("ads 127.0.0.1:"), std::string::npos) << log;
  EXPECT_NE(log.find("(AmsNetId "), std::string::npos) << log;
  EXPECT_NE(log.find(" MAIN.level: "), std::string::npos) << log;
  EXPECT_NE(log.find(" -> 'hello ads'\n"), std::string::npos) << log;
  EXPECT_EQ(log.find(" MAIN.serial: "), std::string::npos) << log;
  EXPECT_EQ(log.find(" MAIN.kMax: "), std::string::npos) << log;
}

// The defaults let 100 client processes of one machine in at once (docs/security.md, Limits):
// a hundred connections from loopback, all open together, each answered.
TEST(AdsE2e, AHundredConnectionsAreAllServedWithTheDefaults) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  std::vector<std::unique_ptr<LoopbackClient>> clients;
  for (int i = 0; i < 100; ++i) {
    clients.push_back(std::make_unique<LoopbackClient>(server->port()));
    ASSERT_TRUE(clients.back()->connected()) << i;
  }
  for (auto& c : clients) ticks(*c);  // expects the read answered without error
  EXPECT_EQ(server->errorOutput().find("refused"), std::string::npos) << server->errorOutput();
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(AdsE2e, AbruptDisconnectsAndGarbageLeaveOthersServed) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  LoopbackClient steady(server->port());
  ASSERT_TRUE(steady.connected());
  const uint32_t before = ticks(steady);
  for (int round = 0; round < 3; ++round) {
    std::vector<std::unique_ptr<LoopbackClient>> crowd;
    for (int i = 0; i < 24; ++i) {
      auto c = std::make_unique<LoopbackClient>(server->port());
      ASSERT_TRUE(c->connected());
      Bytes request = amsPacket(4, {}, static_cast<uint32_t>(i));
      switch (i % 4) {
        case 0: EXPECT_TRUE(c->send(Bytes(request.begin(), request.begin() + 20))); break;  // half a frame, then gone
        case 1: EXPECT_TRUE(c->send({0x00, 0x00, 0x1f, 0x00, 0x00, 0x00})); break;            // too short for an AMS header
        case 2: EXPECT_TRUE(c->send({0x00, 0x00, 0xff, 0xff, 0xff, 0x7f})); break;            // 2 GB frame announced
        default: EXPECT_TRUE(c->send(byName(0xF003, "MAIN.level", 4))); break;                // a handle, never released
      }
      crowd.push_back(std::move(c));
    }
    for (size_t i = 1; i < crowd.size(); i += 4) EXPECT_TRUE(crowd[i]->closedByServer());
    crowd.clear();  // everyone leaves at once, without AMS/TCP port close
  }
  EXPECT_TRUE(steady.send(amsPacket(4, {})));
  Bytes state = frame(steady);
  ASSERT_EQ(state.size(), 46u);
  EXPECT_EQ(state[42], 5);  // still RUN
  // The PLC keeps scanning: MAIN.ticks grows (polled: the rounds above may take less than a scan).
  uint32_t now = before;
  EXPECT_TRUE(eventually([&] { return (now = ticks(steady)) > before; })) << "MAIN.ticks stays at " << now;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(AdsE2e, ReadOnlyServerRefusesWrites) {
  auto server = startServer({"--ads-readonly"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  LoopbackClient c(server->port());
  ASSERT_TRUE(c.send(byName(0xF003, "MAIN.level", 4)));
  Bytes handle = frame(c);
  ASSERT_EQ(adsResult(handle), 0u);
  Bytes write;
  put32(write, 0xF005);
  put32(write, get32(handle, 46));
  put32(write, 2);
  write.push_back(1);
  write.push_back(0);
  ASSERT_TRUE(c.send(amsPacket(3, write)));
  EXPECT_EQ(adsResult(frame(c)), 0x704u);
  ASSERT_TRUE(c.send(amsPacket(5, {6, 0, 0, 0, 0, 0, 0, 0})));  // WriteControl STOP
  EXPECT_EQ(adsResult(frame(c)), 0x704u);
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

// A client's STOP and RUN (WriteControl) change the PLC's state: audited as a record of the PLC
// state, with the client's address and AmsNetId, and counted with the ADS writes.
TEST(AdsE2e, WriteControlIsAuditedAsAStateChange) {
  auto server = startServer({"--audit-writes", "each"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  LoopbackClient c(server->port());
  ASSERT_TRUE(c.send(amsPacket(5, {6, 0, 0, 0, 0, 0, 0, 0})));  // WriteControl STOP
  EXPECT_EQ(adsResult(frame(c)), 0u);
  ASSERT_TRUE(server->waitFor("PLC state: RUN -> STOP\n")) << server->errorOutput();
  ASSERT_TRUE(c.send(amsPacket(5, {5, 0, 0, 0, 0, 0, 0, 0})));  // WriteControl RUN
  EXPECT_EQ(adsResult(frame(c)), 0u);
  ASSERT_TRUE(server->waitFor("PLC state: STOP -> RUN\n")) << server->errorOutput();
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  const std::string log = server->errorOutput();
  EXPECT_NE(log.find(" ads 127.0.0.1:"), std::string::npos) << log;
  EXPECT_NE(log.find("(AmsNetId 10.0.0.1.1.1) PLC state: RUN -> STOP"), std::string::npos) << log;
  EXPECT_NE(log.find("audit: 2 external writes (ads 2, modbus 0, opcua 0, http 0)"), std::string::npos) << log;
}

TEST(AdsE2e, BadOptionsAreUsageErrors) {
  for (auto extra : std::vector<std::vector<std::string>>{{"--ads-netid", "1.2.3"}, {"--ads-allow", "nobody"}}) {
    ServerProcess p(kExe, {"exec", "ads/GVL.st", "ads/MAIN.st", "--ads", "127.0.0.1:0", extra[0], extra[1]}, kDataDir,
                    "ads: serving on ");
    EXPECT_EQ(p.port(), 0);
    EXPECT_EQ(p.waitExit(), 64);
    EXPECT_NE(p.errorOutput().find("error: " + extra[0] + ": '" + extra[1] + "'"), std::string::npos) << p.errorOutput();
  }
}

// --ads-routes FILE (docs/ads.md, Routes): its routes are the peers let in; a mistake stops the
// command at its position.
TEST(AdsE2e, TheRoutesFileLetsItsRoutesInAndOthersOut) {
  const auto dir = std::filesystem::temp_directory_path() / ("virtcom_routes_e2e_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string routes = (dir / "routes.yaml").string(), bad = (dir / "bad.yaml").string();
  std::ofstream(routes) << "routes:\n  - name: tester\n    netid: 10.0.0.1.1.1\n    address: 127.0.0.1\n";
  std::ofstream(bad) << "routes:\n  - name: tester\n    netid: 10.0.0.1\n    address: 127.0.0.1\n";
  {
    auto server = startServer({"--ads-routes", routes});
    ASSERT_GT(server->port(), 0) << server->errorOutput();
    LoopbackClient listed(server->port());
    ticks(listed);  // amsPacket() comes from 10.0.0.1.1.1: on the table, answered
    std::ofstream(routes) << "routes:\n  - name: other\n    netid: 10.0.0.9.1.1\n    address: 127.0.0.1\n";
    EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  }
  {
    auto server = startServer({"--ads-routes", routes});
    ASSERT_GT(server->port(), 0) << server->errorOutput();
    LoopbackClient unlisted(server->port());
    EXPECT_TRUE(unlisted.send(byName(0xF004, "MAIN.ticks", 4)));
    EXPECT_TRUE(unlisted.closedByServer());  // 10.0.0.1.1.1 has no route any more
    EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  }
  ServerProcess p(kExe, {"exec", "ads/GVL.st", "ads/MAIN.st", "--ads", "127.0.0.1:0", "--ads-routes", bad}, kDataDir, "ads: serving on ");
  EXPECT_EQ(p.port(), 0);
  EXPECT_EQ(p.waitExit(), 64);
  EXPECT_NE(p.errorOutput().find("error: --ads-routes: " + bad + ":3:12: error[C010]: 'netid': '10.0.0.1' is not an AmsNetId"),
            std::string::npos)
      << p.errorOutput();
  std::filesystem::remove_all(dir);
}

}  // namespace
