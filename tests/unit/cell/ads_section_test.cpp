// The cell file's `plc: ads:` (docs/ads.md, docs/cell-file.md): its keys, the wiring and run
// variables kept by name for the bridge to resolve, and every mistake at its position.
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
    wiring: { execute: MAIN.pressGo, done: MAIN.pressDone }
    programs:
      1: { name: P, press_time: 1 s, force: 1 kN }
)";

using AdsSection = CellFiles;

TEST_F(AdsSection, TheSettingsAndTheWiringByNameAreKeptForTheBridge) {
  auto cell = loads(std::string("plc:\n  ads:\n    address: 10.1.2.3:48898\n    netid: 10.1.2.3.1.1\n    port: 852\n"
                                "    local_netid: 10.1.2.4.1.1\n    timeout: 250 ms\n    on_loss: hold\n"
                                "    disconnect_when_simulation_stops: false\n"
                                "run:\n  cycle_done: MAIN.cycleDone\n  cycles: 3\n  record: [MAIN.count]\n") +
                    kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->module, nullptr);
  ASSERT_TRUE(cell->plcAds);
  const AdsClientSettings& s = *cell->plcAds;
  EXPECT_EQ(s.address, "10.1.2.3:48898");
  EXPECT_EQ(s.router.ipv4, 0x0a010203u);
  EXPECT_EQ(s.router.port, 48898);
  EXPECT_EQ(s.netId, (AmsNetId{10, 1, 2, 3, 1, 1}));
  EXPECT_EQ(s.port, 852);
  EXPECT_EQ(s.localNetId, (AmsNetId{10, 1, 2, 4, 1, 1}));
  EXPECT_EQ(s.timeoutNs, 250'000'000);
  EXPECT_FALSE(s.faultOnLoss);
  EXPECT_FALSE(s.disconnectWhenStopped);
  EXPECT_EQ(cell->run.cycles, 3u);
  // Clamp by prefix: all five ports, optional; Press port by port; then cycle_done and record.
  ASSERT_EQ(s.wires.size(), 9u);
  EXPECT_EQ(s.wires[0].variable, "MAIN.Clamp.programNumber");
  EXPECT_EQ(s.wires[0].port, "Clamp.programNumber");
  EXPECT_EQ(s.wires[0].dir, plant::PortDir::In);
  EXPECT_TRUE(s.wires[0].optional);
  EXPECT_EQ(s.wires[2].variable, "MAIN.Clamp.done");
  EXPECT_EQ(s.wires[2].dir, plant::PortDir::Out);
  EXPECT_EQ(s.wires[5].variable, "MAIN.pressGo");
  EXPECT_EQ(s.wires[5].port, "Press.execute");
  EXPECT_FALSE(s.wires[5].optional);
  EXPECT_EQ(s.wires[5].loc.line, 22u);
  EXPECT_EQ(s.wires[5].loc.col, 24u);
  EXPECT_EQ(s.wires[7].variable, "MAIN.cycleDone");
  EXPECT_EQ(s.wires[7].tag, cell->run.cycleDoneTag);
  EXPECT_EQ(cell->bus.type(cell->run.cycleDoneTag), ElemType::Bool);
  EXPECT_EQ(s.wires[8].variable, "MAIN.count");
  EXPECT_EQ(s.wires[8].tag, kNoTag);  // its type comes from the PLC
}

TEST_F(AdsSection, MistakesAreReportedAtTheirPosition) {
  EXPECT_THAT(fails(std::string("plc:\n  ads:\n    address: 10.1.2.3\n    netid: 1.2.3\n    port: 0\n    on_loss: retry\n"
                                "    timeout: 0 ms\n    colour: red\n"
                                "run:\n  until: MAIN.count >= 3\n") +
                    kDevices),
              ElementsAre(::testing::HasSubstr("cell.yaml:3:14: error[C010]: 'address': "),
                          "cell.yaml:4:12: error[C010]: 'netid': '1.2.3' is not an AmsNetId (six numbers 0-255, e.g. 192.168.1.10.1.1)",
                          "cell.yaml:5:11: error[C010]: 'port' must be an AMS port 1..65535 (851 = PLC runtime 1)",
                          "cell.yaml:6:14: error[C010]: 'on_loss' must be fault or hold, not 'retry'",
                          "cell.yaml:7:14: error[C010]: 'timeout' must be at least 1 ms",
                          ::testing::HasSubstr("cell.yaml:8:5: error[C011]: "),
                          "cell.yaml:10:10: error[C010]: 'until' needs the soft PLC ('plc: sources'); with 'plc: ads' end the run with "
                          "'cycle_done' or 'time_limit'"));
}

TEST_F(AdsSection, TheAddressIsKeptAsWrittenForMessagesAndParsedForTheBridge) {
  auto cell = loads(std::string("plc:\n  ads: { address: 'localhost:48898' }\n") + kDevices);
  ASSERT_TRUE(cell);
  const AdsClientSettings& s = *cell->plcAds;
  EXPECT_EQ(s.address, "localhost:48898");
  EXPECT_EQ(s.router.ipv4, 0x7f000001u);
  EXPECT_EQ(s.router.port, 48898);
  EXPECT_EQ(s.addressLoc.line, 2u);
  EXPECT_EQ(s.netId, kLocalAliasNetId);
  EXPECT_EQ(s.port, 851);
  EXPECT_FALSE(s.localNetId);
  EXPECT_EQ(s.timeoutNs, 500'000'000);
  EXPECT_TRUE(s.faultOnLoss);
}

// `netid` and `local_netid` share the AmsNetId reader of `--ads-netid` (core/ams_net_id.hpp),
// and `address` the endpoint reader of `plc: modbus:`.
TEST_F(AdsSection, AmsNetIdsAndAddressesAreRefusedInTheSharedReadersWords) {
  EXPECT_THAT(fails(std::string("plc:\n  ads:\n    address: 127.0.0.1:0\n    local_netid: 1.2.3.4.5.300\n") + kDevices),
              ElementsAre("cell.yaml:3:14: error[C010]: 'address': port 0 cannot be connected to (expected HOST:PORT, e.g. "
                          "127.0.0.1:48898)",
                          "cell.yaml:4:18: error[C010]: 'local_netid': " + parseNetId("1.2.3.4.5.300").error()));
}

TEST_F(AdsSection, OneExternalPlcAtATime) {
  write("main.st", kMainSt);
  EXPECT_THAT(fails(std::string("plc:\n  sources: [main.st]\n  ads: { address: 127.0.0.1:48898 }\n") + kDevices),
              ElementsAre("cell.yaml:3:8: error[C010]: 'plc' has either 'sources' (the soft PLC) or 'ads' (an external PLC), not both"));
  EXPECT_THAT(fails(std::string("plc:\n  modbus: { address: 127.0.0.1:502 }\n  ads: { address: 127.0.0.1:48898 }\n") + kDevices),
              ElementsAre("cell.yaml:3:8: error[C010]: 'plc' has either 'modbus' or 'ads' (one external PLC), not both"));
}

}  // namespace
}  // namespace virtcom::cell::test
