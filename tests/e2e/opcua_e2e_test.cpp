// End-to-end: `virtcom exec opcua/GVL.st opcua/MAIN.st --opcua 127.0.0.1:0` in its own process,
// driven by the real npm node-opcua-client (tests/e2e/opcua, installed by `make test` with npm
// ci) and by raw bytes for what a well-behaved client never does: garbage, half messages,
// abrupt disconnects, messages out of order.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/loopback_client.hpp"

namespace {

using Bytes = std::vector<uint8_t>;
using virtcom::e2e::ServerProcess;
using virtcom::test::LoopbackClient;

const std::string kExe = VIRTCOM_EXE;
const std::string kDataDir = VIRTCOM_E2E_DATA;
const std::string kClientDir = VIRTCOM_OPCUA_CLIENT_DIR;

std::unique_ptr<ServerProcess> startServer(std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"exec", "opcua/GVL.st", "opcua/MAIN.st", "--opcua", "127.0.0.1:0"};
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<ServerProcess>(kExe, args, kDataDir, "opcua: serving opc.tcp://");
}

void put32(Bytes& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint32_t get32(const Bytes& b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

// A message of type `type` ("HEL", ...) with `body` (docs/opcua.md, Wire reference: Messages).
Bytes message(const char* type, const Bytes& body, char chunk = 'F') {
  Bytes m{static_cast<uint8_t>(type[0]), static_cast<uint8_t>(type[1]), static_cast<uint8_t>(type[2]), static_cast<uint8_t>(chunk)};
  put32(m, static_cast<uint32_t>(8 + body.size()));
  m.insert(m.end(), body.begin(), body.end());
  return m;
}

Bytes hello() {
  Bytes b;
  for (uint32_t v : {0u, 65536u, 65536u, 0u, 0u}) put32(b, v);
  const std::string url = "opc.tcp://127.0.0.1";
  put32(b, static_cast<uint32_t>(url.size()));
  b.insert(b.end(), url.begin(), url.end());
  return message("HEL", b);
}

// One whole message; empty if the server closed or timed out.
Bytes receiveMessage(LoopbackClient& c) {
  Bytes head = c.receive(8);
  if (head.size() < 8) return {};
  Bytes rest = c.receive(get32(head, 4) - 8);
  head.insert(head.end(), rest.begin(), rest.end());
  return head;
}

std::string typeOf(const Bytes& m) { return m.size() >= 3 ? std::string(m.begin(), m.begin() + 3) : ""; }

TEST(OpcuaE2e, NodeOpcuaClientScenario) {
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/node-opcua-client"))
      << "the npm node-opcua-client is missing: run `npm ci --prefix tests/e2e/opcua` (make test does)";
  // node-opcua's session is anonymous: it writes only because it is allowed to.
  auto server = startServer({"--audit-writes", "each", "--opcua-anonymous", "write"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  std::string output;
  int status = virtcom::e2e::shell("cd '" + kClientDir + "' && node check_opcua_client.js " + std::to_string(server->port()), output);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("ok: "), std::string::npos) << output;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  // Every accepted write audited with the client's address (docs/security.md), the members by name.
  const std::string log = server->errorOutput();
  EXPECT_NE(log.find("opcua 127.0.0.1:"), std::string::npos) << log;
  EXPECT_NE(log.find(" MAIN.level: "), std::string::npos) << log;
  EXPECT_NE(log.find(" MAIN.point.y: "), std::string::npos) << log;
  EXPECT_NE(log.find(" -> -2.5\n"), std::string::npos) << log;
  EXPECT_NE(log.find(" -> 'hello ua'\n"), std::string::npos) << log;
  EXPECT_NE(log.find("audit: "), std::string::npos) << log;
  EXPECT_EQ(log.find("external writes (ads 0, modbus 0, opcua 0"), std::string::npos) << log;
}

TEST(OpcuaE2e, GarbageHalfMessagesAndAbruptDisconnectsLeaveOthersServed) {
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  for (int round = 0; round < 3; ++round) {
    std::vector<std::unique_ptr<LoopbackClient>> crowd;
    for (int i = 0; i < 12; ++i) {
      auto c = std::make_unique<LoopbackClient>(server->port());
      ASSERT_TRUE(c->connected());
      Bytes h = hello();
      switch (i % 4) {
        case 0: EXPECT_TRUE(c->send({'G', 'E', 'T', ' ', '/', ' ', 'H', 'T', 'T', 'P', '/', '1', '.', '1', '\r', '\n'})); break;
        case 1: EXPECT_TRUE(c->send(Bytes(h.begin(), h.begin() + 12))); break;  // half a Hello, then gone
        case 2: EXPECT_TRUE(c->send({'H', 'E', 'L', 'F', 0xff, 0xff, 0xff, 0x7f})); break;  // 2 GB announced
        default: EXPECT_TRUE(c->send(message("MSG", Bytes(16, 0)))); break;  // MSG before HEL
      }
      crowd.push_back(std::move(c));
    }
    for (size_t i = 0; i < crowd.size(); ++i) {
      if (i % 4 == 1) continue;
      // Answered with ERR, then closed.
      Bytes err = receiveMessage(*crowd[i]);
      EXPECT_EQ(typeOf(err), "ERR") << i;
      EXPECT_TRUE(crowd[i]->closedByServer()) << i;
    }
    crowd.clear();  // everyone leaves at once
  }
  LoopbackClient steady(server->port());
  ASSERT_TRUE(steady.connected());
  ASSERT_TRUE(steady.send(hello()));
  Bytes ack = receiveMessage(steady);
  ASSERT_EQ(typeOf(ack), "ACK");
  EXPECT_EQ(ack.size(), 28u);
  EXPECT_EQ(get32(ack, 8), 0u);  // protocol version
  // An OPN with another security policy is refused with ERR BadSecurityPolicyRejected.
  Bytes open;
  put32(open, 0);
  const std::string policy = "http://opcfoundation.org/UA/SecurityPolicy#Basic256Sha256";
  put32(open, static_cast<uint32_t>(policy.size()));
  open.insert(open.end(), policy.begin(), policy.end());
  for (int i = 0; i < 4; ++i) put32(open, i < 2 ? 0xFFFFFFFF : 1);
  ASSERT_TRUE(steady.send(message("OPN", open)));
  Bytes refused = receiveMessage(steady);
  ASSERT_EQ(typeOf(refused), "ERR");
  EXPECT_EQ(get32(refused, 8), 0x80550000u);
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(OpcuaE2e, BadEndpointIsAClearError) {
  std::string out;
  int status = virtcom::e2e::shell("cd '" + kDataDir + "' && '" + kExe + "' exec opcua/GVL.st opcua/MAIN.st --opcua 127.0.0.1:99999", out);
  EXPECT_EQ(status, 64) << out;
  EXPECT_NE(out.find("error: --opcua: "), std::string::npos) << out;
  out.clear();
  status = virtcom::e2e::shell("cd '" + kDataDir + "' && '" + kExe + "' exec opcua/GVL.st opcua/MAIN.st --opcua 127.0.0.1:0 --opcua-allow 1.2.3", out);
  EXPECT_EQ(status, 64) << out;
  EXPECT_NE(out.find("error: --opcua-allow: "), std::string::npos) << out;
}

TEST(OpcuaE2e, ServeCellsSoftPlcOverOpcua) {
  // examples/ads-cell's soft PLC, served while the cell runs: node-opcua reads and browses it.
  ServerProcess server(kExe, {"serve", "cell.yaml", "--opcua", "127.0.0.1:0"}, VIRTCOM_SOURCE_DIR "/examples/ads-cell",
                       "opcua: serving opc.tcp://");
  ASSERT_GT(server.port(), 0) << server.errorOutput();
  const std::string script =
      "const u=require('node-opcua-client');(async()=>{const c=u.OPCUAClient.create({endpointMustExist:false,"
      "connectionStrategy:{maxRetry:0}});await c.connect('opc.tcp://127.0.0.1:" + std::to_string(server.port()) +
      "');const s=await c.createSession();const b=await s.browse('ns=0;i=85');"
      "console.log('folders',b.references.map(r=>r.browseName.name).join(','));await s.close();await c.disconnect();})()"
      ".catch(e=>{console.error(e);process.exit(1);});";
  std::string output;
  int status = virtcom::e2e::shell("cd '" + kClientDir + "' && node -e \"" + script + "\"", output);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("folders Server,"), std::string::npos) << output;
  EXPECT_EQ(server.stop(), 0) << server.errorOutput();
}

// The cell's devices as objects: check_opcua_devices.js browses Objects/Devices, reads each
// signal's type, sees the clamp's `done` change while the cell runs, its `execute` equal to the PLC
// variable wired to it in every Read (one image of a scan), and a write refused.
TEST(OpcuaE2e, ServeCellsDevicesAsObjectsOfTheirSignals) {
  ServerProcess server(kExe, {"serve", "cell.yaml", "--opcua", "127.0.0.1:0"}, VIRTCOM_SOURCE_DIR "/examples/ads-cell",
                       "opcua: serving opc.tcp://");
  ASSERT_GT(server.port(), 0) << server.errorOutput();
  std::string output;
  int status = virtcom::e2e::shell("cd '" + kClientDir + "' && node check_opcua_devices.js " + std::to_string(server.port()), output);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("device Clamp: programNumber:Int16 execute:Boolean done:Boolean error:Int16 busy:Boolean"), std::string::npos)
      << output;
  EXPECT_NE(output.find("actualForce:Double position:Double"), std::string::npos) << output;
  EXPECT_NE(output.find("write refused: BadNotWritable"), std::string::npos) << output;
  EXPECT_EQ(server.stop(), 0) << server.errorOutput();
}

// `monitor --serve-opcua` serves the watched cell's devices as `serve --opcua` does, their values
// those the monitor read from the plant's PLC (here `serve --ads` plays the plant), read only.
TEST(OpcuaE2e, MonitorServesTheWatchedDevicesOverOpcua) {
  const std::string example = VIRTCOM_SOURCE_DIR "/examples/ads-cell";
  ServerProcess plant(kExe, {"serve", "cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, example, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", "cell.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--serve-opcua", "127.0.0.1:0",
                         "--serve-opcua-anonymous", "write", "--quiet"},
                        example, "opcua: serving opc.tcp://");
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  std::string output;
  EXPECT_EQ(virtcom::e2e::shell("cd '" + kClientDir + "' && node check_opcua_devices.js " + std::to_string(monitor.port()) + " watched",
                                output),
            0)
      << output;
  EXPECT_NE(output.find("device Clamp: programNumber:Int16 execute:Boolean done:Boolean error:Int16 busy:Boolean"), std::string::npos)
      << output;
  EXPECT_NE(output.find("devices ok"), std::string::npos) << output;
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
}

// A users file made by `virtcom opcua-user add` (the passwords on stdin), in a fresh folder.
std::string makeUsersFile() {
  const auto dir = std::filesystem::temp_directory_path() / ("virtcom-opcua-users-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "users.txt").string();
  std::filesystem::remove(file);
  std::string out;
  const std::string add = "' | '" + kExe + "' opcua-user add '" + file + "' ";
  EXPECT_EQ(virtcom::e2e::shell("printf 'op-pass\\n" + add + "operator --role read-write", out), 0) << out;
  EXPECT_NE(out.find("added operator (read-write)"), std::string::npos) << out;
  EXPECT_EQ(virtcom::e2e::shell("printf 'first\\n" + add + "viewer", out), 0) << out;
  // Again: the password is replaced, not a second line added.
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell("printf 'view-pass\\n" + add + "viewer", out), 0) << out;
  EXPECT_NE(out.find("updated viewer (read-only)"), std::string::npos) << out;
  return file;
}

TEST(OpcuaE2e, UsersFileIdentities) {
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/node-opcua-client"))
      << "the npm node-opcua-client is missing: run `npm ci --prefix tests/e2e/opcua` (make test does)";
  const std::string users = makeUsersFile();
  std::string text, out;
  EXPECT_EQ(virtcom::e2e::shell("cat '" + users + "'", text), 0);
  EXPECT_EQ(text.find("op-pass"), std::string::npos) << "passwords are stored as hashes: " << text;
  EXPECT_EQ(std::filesystem::status(users).permissions() & std::filesystem::perms::others_read, std::filesystem::perms::none);
  auto server = startServer({"--opcua-users", users});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  EXPECT_TRUE(server->waitFor("(security None, 2 users)")) << server->errorOutput();
  const std::string client = "cd '" + kClientDir + "' && node check_opcua_identity.js ";
  EXPECT_EQ(virtcom::e2e::shell(client + std::to_string(server->port()), out), 0) << out;
  EXPECT_NE(out.find("ok: identities"), std::string::npos) << out;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  // Anonymous allowed to read beside the users.
  server = startServer({"--opcua-users", users, "--opcua-anonymous", "read"});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  EXPECT_TRUE(server->waitFor("(security None, anonymous read-only, 2 users)")) << server->errorOutput();
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell(client + std::to_string(server->port()) + " anonymous-read", out), 0) << out;
  EXPECT_NE(out.find("ok: identities"), std::string::npos) << out;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  std::filesystem::remove_all(std::filesystem::path(users).parent_path());
}

TEST(OpcuaE2e, AnonymousReadsButMayNotWriteByDefault) {
  // Issue 20: "writing disabled for anonymous unless configured", with or without a users file.
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/node-opcua-client"))
      << "the npm node-opcua-client is missing: run `npm ci --prefix tests/e2e/opcua` (make test does)";
  auto server = startServer();
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  EXPECT_TRUE(server->waitFor("(security None, anonymous read-only)")) << server->errorOutput();
  std::string out;
  const std::string client = "cd '" + kClientDir + "' && node check_opcua_identity.js ";
  EXPECT_EQ(virtcom::e2e::shell(client + std::to_string(server->port()) + " anonymous-only", out), 0) << out;
  EXPECT_NE(out.find("ok: anonymous reads only"), std::string::npos) << out;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
}

TEST(OpcuaE2e, SecuredEndpointsAndTheTrustListWithNodeOpcua) {
  // Issue 20: Basic256Sha256 Sign and SignAndEncrypt with a generated self-signed certificate and
  // a trust list, driven by node-opcua-client with its own certificate (check_opcua_security.js).
  ASSERT_TRUE(std::filesystem::exists(kClientDir + "/node_modules/node-opcua-client"))
      << "the npm node-opcua-client is missing: run `npm ci --prefix tests/e2e/opcua` (make test does)";
  const std::string users = makeUsersFile();
  const auto dir = std::filesystem::path(users).parent_path();
  const std::string pki = (dir / "server-pki").string(), clientPki = (dir / "client-pki").string();
  auto server = startServer({"--opcua-users", users, "--opcua-security", "none,sign,sign-encrypt", "--opcua-pki", pki});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  EXPECT_TRUE(server->waitFor("(security None, Basic256Sha256 Sign, Basic256Sha256 SignAndEncrypt, PKI " + pki + ", 2 users)"))
      << server->errorOutput();
  EXPECT_TRUE(std::filesystem::exists(pki + "/own/certs/virtcom.der")) << "generated at first start";
  EXPECT_EQ(std::filesystem::status(pki + "/own/private").permissions() & std::filesystem::perms::group_all,
            std::filesystem::perms::none);
  const std::string client = "cd '" + kClientDir + "' && node check_opcua_security.js " + std::to_string(server->port()) + " '" +
                             clientPki + "' ";
  std::string out;
  EXPECT_EQ(virtcom::e2e::shell(client + "untrusted", out), 0) << out;
  EXPECT_NE(out.find("ok: untrusted refused"), std::string::npos) << out;
  // The operator is told which file to move; doing so trusts the client (no restart).
  EXPECT_TRUE(server->waitFor("the client certificate is not trusted; to trust it, move " + pki + "/rejected/certs/"))
      << server->errorOutput();
  std::vector<std::filesystem::path> rejected;
  for (const auto& entry : std::filesystem::directory_iterator(pki + "/rejected/certs")) rejected.push_back(entry.path());
  ASSERT_EQ(rejected.size(), 1u);
  std::filesystem::rename(rejected[0], pki + "/trusted/certs/" + rejected[0].filename().string());
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell(client + "trusted", out), 0) << out;
  EXPECT_NE(out.find("ok: secured"), std::string::npos) << out;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  // A second start keeps the certificate the clients know.
  const auto certificateTime = std::filesystem::last_write_time(pki + "/own/certs/virtcom.der");
  server = startServer({"--opcua-security", "sign-encrypt", "--opcua-pki", pki});
  ASSERT_GT(server->port(), 0) << server->errorOutput();
  EXPECT_TRUE(server->waitFor("(security Basic256Sha256 SignAndEncrypt, PKI ")) << server->errorOutput();
  EXPECT_EQ(std::filesystem::last_write_time(pki + "/own/certs/virtcom.der"), certificateTime);
  // Without a None endpoint: discovery over a None channel still works, a session needs security.
  const std::string again = "cd '" + kClientDir + "' && node check_opcua_security.js " + std::to_string(server->port()) + " '" +
                            clientPki + "' encrypt-only";
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell(again, out), 0) << out;
  EXPECT_NE(out.find("ok: encrypt-only"), std::string::npos) << out;
  EXPECT_EQ(server->stop(), 0) << server->errorOutput();
  std::filesystem::remove_all(dir);
}

TEST(OpcuaE2e, SecurityOptionErrors) {
  std::string out;
  const std::string exec = "cd '" + kDataDir + "' && '" + kExe + "' exec opcua/GVL.st opcua/MAIN.st --cycles 1 --opcua 127.0.0.1:0 ";
  EXPECT_EQ(virtcom::e2e::shell(exec + "--opcua-security none,encrypt", out), 64) << out;
  EXPECT_NE(out.find("--opcua-security: unknown mode 'encrypt'; expected a comma list of none, sign, sign-encrypt"), std::string::npos)
      << out;
  out.clear();
  const std::string file = (std::filesystem::temp_directory_path() / ("virtcom-pki-file-" + std::to_string(::getpid()))).string();
  EXPECT_EQ(virtcom::e2e::shell("touch '" + file + "' && " + exec + "--opcua-security sign --opcua-pki '" + file + "'", out), 64) << out;
  EXPECT_NE(out.find("--opcua-pki: "), std::string::npos) << out;
  EXPECT_NE(out.find(file), std::string::npos) << out;
  std::filesystem::remove(file);
}

TEST(OpcuaE2e, IdentityOptionErrors) {
  std::string out;
  const std::string exec = "cd '" + kDataDir + "' && '" + kExe + "' exec opcua/GVL.st opcua/MAIN.st --cycles 1 --opcua 127.0.0.1:0 ";
  EXPECT_EQ(virtcom::e2e::shell(exec + "--opcua-anonymous none", out), 64) << out;
  EXPECT_NE(out.find("--opcua-anonymous none: nobody could log on; give --opcua-users FILE too"), std::string::npos) << out;
  const std::string bad = (std::filesystem::temp_directory_path() / ("virtcom-bad-users-" + std::to_string(::getpid()))).string();
  out.clear();
  const std::string writeBad = "printf '# users\\nop:admin:x\\n' > '" + bad + "' && ";
  EXPECT_EQ(virtcom::e2e::shell(writeBad + exec + "--opcua-users '" + bad + "'", out), 64) << out;
  EXPECT_NE(out.find(bad + ":2:1: expected 6 fields"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell("'" + kExe + "' opcua-user add '" + bad + ".new' op < /dev/null", out), 64) << out;
  EXPECT_NE(out.find("no password on stdin"), std::string::npos) << out;
  std::filesystem::remove(bad);
}

TEST(OpcuaE2e, HelpNamesTheOptions) {
  std::string out;
  EXPECT_EQ(virtcom::e2e::shell("'" + kExe + "' exec --help", out), 0) << out;
  for (const char* command : {"exec", "serve"}) {
    out.clear();
    EXPECT_EQ(virtcom::e2e::shell("'" + kExe + "' " + command + " --help", out), 0) << out;
    for (const char* option :
         {"--opcua ", "--opcua-allow", "--opcua-readonly", "--opcua-max-sessions", "--opcua-users", "--opcua-anonymous",
          "--opcua-security", "--opcua-pki", "--opcua-trust-any-client"})
      EXPECT_NE(out.find(option), std::string::npos) << command << " " << option;
  }
  out.clear();
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell("'" + kExe + "' monitor --help", out), 0) << out;
  for (const char* option : {"--serve-opcua ", "--serve-opcua-allow", "--serve-opcua-users", "--serve-opcua-security", "--serve-opcua-pki"})
    EXPECT_NE(out.find(option), std::string::npos) << "monitor " << option;
  out.clear();
  EXPECT_EQ(virtcom::e2e::shell("'" + kExe + "' opcua-user add --help", out), 0) << out;
  EXPECT_NE(out.find("--role"), std::string::npos) << out;
}

}  // namespace
