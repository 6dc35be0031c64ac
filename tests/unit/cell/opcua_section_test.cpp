// The cell file's `plc: opcua:` (docs/opcua.md, docs/cell-file.md): its keys, the wiring and run
// variables kept by name for the bridge (as `plc: ads:`), and every mistake at its position.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cell_files.hpp"

namespace virtcom::cell::test {
namespace {

using ::testing::ElementsAre;

constexpr const char* kDevices = R"(devices:
  - name: Clamp
    type: timed
    wiring: MAIN.Clamp
    commands:
      1: { name: Close, duration: 1 s }
  - name: Press
    type: press
    wiring: { execute: MAIN.pressGo, done: "ns=2;i=17" }
    programs:
      1: { name: P, press_time: 1 s, force: 1 kN }
)";

using OpcuaSection = CellFiles;

TEST_F(OpcuaSection, TheSettingsAndTheWiringByNameAreKeptForTheBridge) {
  auto cell = loads(std::string("plc:\n  opcua:\n    endpoint: opc.tcp://10.1.2.3:4841/PLC\n    security: none\n"
                                "    user: operator\n    password: op-pass\n    node_prefix: 'ns=3;s=\"'\n"
                                "    nodes: { MAIN.pressGo: 'ns=2;s=go', MAIN.count: /4:MAIN/4:count }\n    poll: 20 ms\n    subscribe: false\n    timeout: 250 ms\n    on_loss: hold\n"
                                "    disconnect_when_simulation_stops: false\n"
                                "run:\n  cycle_done: MAIN.cycleDone\n  cycles: 3\n  record: [MAIN.count]\n") +
                    kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->module, nullptr);
  EXPECT_FALSE(cell->plcAds);
  ASSERT_TRUE(cell->plcOpcua);
  const OpcuaClientSettings& s = *cell->plcOpcua;
  EXPECT_EQ(s.url, "opc.tcp://10.1.2.3:4841/PLC");
  EXPECT_EQ(s.server.ipv4, 0x0a010203u);
  EXPECT_EQ(s.server.port, 4841);
  EXPECT_EQ(s.endpointLoc.line, 3u);
  EXPECT_EQ(s.user, "operator");
  EXPECT_EQ(s.password, "op-pass");
  EXPECT_EQ(s.nodePrefix, "ns=3;s=\"");
  ASSERT_EQ(s.nodes.size(), 2u);
  EXPECT_EQ(s.nodes[0].variable, "MAIN.pressGo");
  EXPECT_EQ(s.nodes[0].node, "ns=2;s=go");
  EXPECT_EQ(s.nodes[1].node, "/4:MAIN/4:count") << "a browse path, checked when the bridge starts";
  EXPECT_EQ(s.nodes[1].loc.line, 8u) << "its problems are reported where it is written";
  EXPECT_EQ(s.pollNs, 20'000'000);
  EXPECT_FALSE(s.subscribe);
  EXPECT_EQ(s.timeoutNs, 250'000'000);
  EXPECT_FALSE(s.faultOnLoss);
  EXPECT_FALSE(s.disconnectWhenStopped);
  // Clamp by prefix: all five ports, optional; Press port by port; then cycle_done and record.
  ASSERT_EQ(s.wires.size(), 9u);
  EXPECT_EQ(s.wires[0].variable, "MAIN.Clamp.programNumber");
  EXPECT_TRUE(s.wires[0].optional);
  EXPECT_EQ(s.wires[5].variable, "MAIN.pressGo");
  EXPECT_EQ(s.wires[6].variable, "ns=2;i=17");
  EXPECT_EQ(s.wires[6].port, "Press.done");
  EXPECT_EQ(s.wires[7].variable, "MAIN.cycleDone");
  EXPECT_EQ(s.wires[7].tag, cell->run.cycleDoneTag);
  EXPECT_EQ(s.wires[8].variable, "MAIN.count");
}

TEST_F(OpcuaSection, TheDefaultsAreVirtcomsOwnServerAnonymously) {
  auto cell = loads(std::string("plc:\n  opcua: { endpoint: 'opc.tcp://localhost:4840' }\n") + kDevices);
  ASSERT_TRUE(cell);
  const OpcuaClientSettings& s = *cell->plcOpcua;
  EXPECT_EQ(s.server.ipv4, 0x7f000001u);
  EXPECT_EQ(s.server.port, 4840);
  EXPECT_TRUE(s.user.empty());
  EXPECT_EQ(s.nodePrefix, "ns=4;s=|var|virtcom.Application.");
  EXPECT_EQ(s.pollNs, 10'000'000);
  EXPECT_TRUE(s.subscribe);
  EXPECT_EQ(s.timeoutNs, 500'000'000);
  EXPECT_TRUE(s.faultOnLoss);
  EXPECT_TRUE(s.disconnectWhenStopped);
}

TEST_F(OpcuaSection, MistakesAreReportedAtTheirPosition) {
  EXPECT_THAT(fails(std::string("plc:\n  opcua:\n    endpoint: http://10.1.2.3:4840\n    security: basic256sha256\n"
                                "    user: operator\n    nodes: [a, b]\n    on_loss: retry\n    poll: 0 s\n    colour: red\n"
                                "run:\n  until: MAIN.count >= 3\n") +
                    kDevices),
              ElementsAre("cell.yaml:3:15: error[C010]: 'endpoint': 'http://10.1.2.3:4840' is not an opc.tcp URL (expected "
                          "opc.tcp://HOST:PORT, e.g. opc.tcp://127.0.0.1:4840)",
                          "cell.yaml:4:15: error[C010]: 'security' must be none, sign or sign-encrypt (Basic256Sha256), not "
                          "'basic256sha256'",
                          "cell.yaml:5:11: error[C010]: 'user' and 'password' go together (a UserName identity); leave both out for an "
                          "anonymous session",
                          "cell.yaml:6:12: error[C010]: 'nodes' must be a map PLC variable: node id or browse path (MAIN.start: \"ns=2;i=17\" or \"/4:MAIN/4:start\")",
                          "cell.yaml:7:14: error[C010]: 'on_loss' must be fault or hold, not 'retry'",
                          "cell.yaml:8:11: error[C010]: 'poll' must be at least 1 ms",
                          ::testing::HasSubstr("cell.yaml:9:5: error[C011]: "),
                          "cell.yaml:11:10: error[C010]: 'until' needs the soft PLC ('plc: sources'); with 'plc: opcua' end the run "
                          "with 'cycle_done' or 'time_limit'"));
  EXPECT_THAT(fails(std::string("plc:\n  opcua: { endpoint: 'opc.tcp://127.0.0.1:0' }\n") + kDevices),
              ElementsAre("cell.yaml:2:22: error[C010]: 'endpoint': port 0 cannot be connected to (expected opc.tcp://HOST:PORT, e.g. "
                          "opc.tcp://127.0.0.1:4840)"));
  EXPECT_THAT(fails(std::string("plc:\n  opcua: { security: none }\n") + kDevices),
              ElementsAre(::testing::HasSubstr("cell.yaml:2:10: error[C0")));
}

TEST_F(OpcuaSection, SecurityKeysAndTheirMistakes) {
  auto cell = loads(std::string("plc:\n  opcua:\n    endpoint: opc.tcp://10.1.2.3:4841\n    security: sign-encrypt\n"
                                "    pki: keys/opcua\n    trust_server: any\n") +
                    kDevices);
  ASSERT_TRUE(cell);
  const OpcuaClientSettings& s = *cell->plcOpcua;
  EXPECT_EQ(s.security, OpcuaSecurity::SignAndEncrypt);
  EXPECT_EQ(s.pkiDir, path("keys/opcua")) << "relative to the cell file's folder";
  EXPECT_TRUE(s.trustAnyServer);
  cell = loads(std::string("plc:\n  opcua: { endpoint: 'opc.tcp://127.0.0.1:4840', security: sign }\n") + kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->plcOpcua->security, OpcuaSecurity::Sign);
  EXPECT_TRUE(cell->plcOpcua->pkiDir.empty()) << "the default folder";
  EXPECT_FALSE(cell->plcOpcua->trustAnyServer);
  EXPECT_THAT(fails(std::string("plc:\n  opcua:\n    endpoint: opc.tcp://10.1.2.3:4841\n    pki: keys\n    trust_server: all\n") +
                    kDevices),
              ElementsAre("cell.yaml:4:10: error[C010]: 'pki' is for a secured link: it needs 'security: sign' or 'security: "
                          "sign-encrypt'",
                          "cell.yaml:5:19: error[C010]: 'trust_server' can only be 'any' (every server certificate, for labs), not "
                          "'all'; leave it out to trust the certificates in the PKI folder's trusted/certs",
                          "cell.yaml:5:19: error[C010]: 'trust_server' is for a secured link: it needs 'security: sign' or "
                          "'security: sign-encrypt'"));
}

TEST_F(OpcuaSection, OneExternalPlcAtATime) {
  write("main.st", kMainSt);
  EXPECT_THAT(fails(std::string("plc:\n  sources: [main.st]\n  opcua: { endpoint: 'opc.tcp://127.0.0.1:4840' }\n") + kDevices),
              ElementsAre("cell.yaml:3:10: error[C010]: 'plc' has either 'sources' (the soft PLC) or 'opcua' (an external PLC), not both"));
  EXPECT_THAT(fails(std::string("plc:\n  ads: { address: 127.0.0.1:48898 }\n  opcua: { endpoint: 'opc.tcp://127.0.0.1:4840' }\n") + kDevices),
              ElementsAre("cell.yaml:3:10: error[C010]: 'plc' has either 'ads' or 'opcua' (one external PLC), not both"));
}

}  // namespace
}  // namespace virtcom::cell::test
