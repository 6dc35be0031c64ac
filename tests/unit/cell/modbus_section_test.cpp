// The cell file's Modbus parts (docs/modbus.md): the served map (`modbus:` or automatic), the
// client bridge (`plc: modbus:`), cells without a soft PLC, and every mistake at its position.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cell_files.hpp"
#include "core/modbus_map.hpp"

namespace virtcom::cell::test {
namespace {

using ::testing::ElementsAre;
namespace mb = modbus_map;

// A clamp (command port INT `programNumber`, execute; status done, error, busy) and a press
// (adds LREAL actualForce and position), no soft PLC.
constexpr const char* kDevices = R"(devices:
  - name: Clamp
    type: timed
    commands:
      1: { name: Close, duration: 1 s }
  - name: Press
    type: press
    programs:
      1: { name: P, press_time: 1 s, force: 1 kN }
)";

using ModbusSection = CellFiles;

TEST_F(ModbusSection, ACellWithoutPlcHasNoControllerAndAnAutomaticMap) {
  auto cell = loads(std::string("name: served\n") + kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->module, nullptr);
  EXPECT_FALSE(cell->plcModbus);
  EXPECT_TRUE(cell->modbus.automatic);
  EXPECT_EQ(mb::formatMapCsv(cell->modbus),
            "table,address,type,signal,direction,access,word_order,scale\n"
            "holding,0,INT,Clamp.programNumber,command,read/write,,1\n"
            "coil,0,BOOL,Clamp.execute,command,read/write,,\n"
            "discrete,0,BOOL,Clamp.done,status,read,,\n"
            "input,0,INT,Clamp.error,status,read,,1\n"
            "discrete,1,BOOL,Clamp.busy,status,read,,\n"
            "holding,1,INT,Press.programNumber,command,read/write,,1\n"
            "coil,1,BOOL,Press.execute,command,read/write,,\n"
            "discrete,2,BOOL,Press.done,status,read,,\n"
            "input,1,INT,Press.error,status,read,,1\n"
            "discrete,3,BOOL,Press.busy,status,read,,\n"
            "input,2,REAL,Press.actualForce,status,read,high_first,1\n"
            "input,4,REAL,Press.position,status,read,high_first,1\n");
}

TEST_F(ModbusSection, AnExplicitMapWithTypesWordOrderScaleAndReadOnly) {
  auto cell = loads(std::string("plc:\n  cycle_time: 5 ms\n") + kDevices +
                    "modbus:\n"
                    "  word_order: low_first\n"
                    "  map:\n"
                    "    - { signal: Clamp.execute, table: coil, address: 8, read_only: true }\n"
                    "    - { signal: Press.actualForce, table: holding, address: 100, type: DINT, scale: 0.5 }\n"
                    "    - { signal: Press.position, table: input, type: REAL, word_order: high_first }\n"
                    "    - { signal: Press.position }\n");
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->run.plcCycleNs, 5'000'000);
  EXPECT_EQ(mb::formatMapMarkdown(cell->modbus),
            "| table | address | type | signal | direction | access | word order | scale |\n"
            "| --- | ---: | --- | --- | --- | --- | --- | ---: |\n"
            "| coil | 8 | BOOL | `Clamp.execute` | command | read |  |  |\n"
            "| holding | 100 | DINT | `Press.actualForce` | status | read | low_first | 0.5 |\n"
            "| input | 0 | REAL | `Press.position` | status | read | high_first | 1 |\n"
            "| input | 2 | REAL | `Press.position` | status | read | low_first | 1 |\n");
}

TEST_F(ModbusSection, EveryMapMistakeAtItsPosition) {
  EXPECT_THAT(fails(std::string(kDevices) +                                               // 1-9
                    "modbus:\n"                                                           // 10
                    "  word_order: middle\n"                                              // 11
                    "  map:\n"                                                            // 12
                    "    - { signal: Clamp.exec }\n"                                      // 13
                    "    - { signal: Clamp.execute, table: input }\n"                     // 14
                    "    - { signal: Clamp.done, table: coil, address: 0 }\n"             // 15
                    "    - { signal: Clamp.busy, table: coil, address: 0 }\n"             // 16
                    "    - { signal: Press.error, table: coil }\n"                        // 17
                    "    - { signal: Press.error, type: LREAL }\n"                        // 18
                    "    - { signal: Press.position, scale: 0 }\n"                        // 19
                    "    - { signal: Press.done, read_only: false }\n"                    // 20
                    "    - { signal: Press.busy, adress: 3 }\n"                           // 21
                    "    - { signal: Press.actualForce, table: holding, address: 65535, type: REAL }\n"  // 22
                    "    - { signal: Clamp.programNumber }\n"                             // 23
                    "    - { signal: Clamp.programNumber }\n"),                           // 24
              ElementsAre("cell.yaml:11:15: error[C010]: 'word_order' must be high_first or low_first, not 'middle'",
                          "cell.yaml:13:17: error[C010]: no device signal 'Clamp.exec' (signals are DEVICE.PORT, e.g. "
                          "Clamp.programNumber, Clamp.execute, Clamp.done, ...)",
                          "cell.yaml:14:39: error[C010]: 'Clamp.execute' is a command the external PLC writes: map it to a "
                          "coil or holding register, not input",
                          "cell.yaml:16:7: error[C010]: coil 0 overlaps 'Clamp.done' at 0",
                          "cell.yaml:17:37: error[C010]: 'Press.error' is INT: map it to a register, a coil holds one bit",
                          "cell.yaml:18:36: error[C010]: 'type' must be BOOL, INT, UINT, DINT, UDINT or REAL, not 'LREAL'",
                          "cell.yaml:19:40: error[C010]: 'scale' must be a non-zero number (signal value = register value * "
                          "scale)",
                          "cell.yaml:20:40: error[C010]: 'Press.done' is a device status signal: it is always read-only",
                          "cell.yaml:21:29: error[C011]: unknown key 'adress' in a Modbus map entry (expected one of: signal, "
                          "table, type, word_order, scale, read_only)",
                          "cell.yaml:22:61: error[C010]: 'address' must be 0..65534 for a REAL",
                          "cell.yaml:24:7: error[C010]: 'Clamp.programNumber' is mapped twice: a command has one writer"));
}

TEST_F(ModbusSection, AStringTypeIsRefusedWithTheReason) {
  EXPECT_THAT(fails(std::string(kDevices) + "modbus:\n  map:\n    - { signal: Press.error, type: STRING }\n"),
              ElementsAre("cell.yaml:12:36: error[C010]: 'type' must be BOOL, INT, UINT, DINT, UDINT or REAL, not "
                          "'STRING' (no device signal carries text, so a signal cannot be mapped as a STRING)"));
}

TEST_F(ModbusSection, TheClientBridgeSettingsAndItsMapDefaults) {
  auto cell = loads(std::string("plc:\n"
                                "  modbus: { address: 127.0.0.1:1502, unit: 3, poll: 20 ms, on_loss: hold }\n") +
                    kDevices);
  ASSERT_TRUE(cell);
  ASSERT_TRUE(cell->plcModbus);
  const ModbusClientSettings& s = *cell->plcModbus;
  EXPECT_EQ(s.address, "127.0.0.1:1502");
  EXPECT_EQ(s.peer.ipv4, 0x7f000001u);
  EXPECT_EQ(s.peer.port, 1502);
  EXPECT_EQ(s.unit, 3);
  EXPECT_EQ(s.pollNs, 20'000'000);
  EXPECT_EQ(s.timeoutNs, 500'000'000);
  EXPECT_FALSE(s.faultOnLoss);
  // commands first (read from the PLC), then status (written to it), all to writable tables
  EXPECT_EQ(mb::formatMapCsv(s.map),
            "table,address,type,signal,direction,access,word_order,scale\n"
            "holding,0,INT,Clamp.programNumber,command,read/write,,1\n"
            "coil,0,BOOL,Clamp.execute,command,read/write,,\n"
            "holding,1,INT,Press.programNumber,command,read/write,,1\n"
            "coil,1,BOOL,Press.execute,command,read/write,,\n"
            "coil,2,BOOL,Clamp.done,status,read/write,,\n"
            "holding,2,INT,Clamp.error,status,read/write,,1\n"
            "coil,3,BOOL,Clamp.busy,status,read/write,,\n"
            "coil,4,BOOL,Press.done,status,read/write,,\n"
            "holding,3,INT,Press.error,status,read/write,,1\n"
            "coil,5,BOOL,Press.busy,status,read/write,,\n"
            "holding,4,REAL,Press.actualForce,status,read/write,high_first,1\n"
            "holding,6,REAL,Press.position,status,read/write,high_first,1\n");
}

// An external Modbus PLC's cycle marker: read from where `cycle_done:` places it (any table a
// client can read, after the map), the run counts its rising edges.
TEST_F(ModbusSection, TheClientBridgeReadsThePlcsCycleMarkerWhereCycleDoneSays) {
  auto cell = loads(std::string("plc:\n"
                                "  modbus:\n"
                                "    address: 127.0.0.1:1502\n"
                                "    map:\n"
                                "      - { signal: Clamp.execute, table: coil, address: 0 }\n"
                                "    cycle_done: { table: coil, address: 2 }\n") +
                    kDevices);
  ASSERT_TRUE(cell);
  const mb::SignalMap& map = cell->plcModbus->map;
  ASSERT_NE(map.cycleDone, kNoTag);
  EXPECT_EQ(cell->run.cycleDoneTag, map.cycleDone);
  EXPECT_EQ(cell->bus.name(map.cycleDone), "plc.cycle_done");
  EXPECT_EQ(mb::formatMapCsv(map),
            "table,address,type,signal,direction,access,word_order,scale\n"
            "coil,0,BOOL,Clamp.execute,command,read/write,,\n"
            "coil,2,BOOL,plc.cycle_done,command,read/write,,\n");

  cell = loads(std::string("plc:\n  modbus: { address: 127.0.0.1:1502 }\n") + kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->run.cycleDoneTag, kNoTag) << "no cycle_done: no cycles counted";
  EXPECT_EQ(cell->bus.find("plc.cycle_done"), kNoTag);
  EXPECT_THAT(fails(std::string("plc:\n  modbus:\n    address: 127.0.0.1:1502\n    cycle_done: { table: coil, address: -1 }\n") +
                    kDevices),
              ElementsAre(::testing::HasSubstr("cell.yaml:4:")));
}

TEST_F(ModbusSection, ClientBridgeMistakes) {
  EXPECT_THAT(fails(std::string("plc:\n"
                                "  modbus:\n"
                                "    address: 127.0.0.1\n"
                                "    unit: 300\n"
                                "    poll: 0.1 ms\n"
                                "    on_loss: ignore\n"
                                "    map:\n"
                                "      - { signal: Clamp.done, table: discrete }\n"
                                "run:\n"
                                "  until: MAIN.done\n") +
                    kDevices),
              ElementsAre("cell.yaml:3:14: error[C010]: 'address': expected HOST:PORT, found '127.0.0.1' (expected "
                          "HOST:PORT, e.g. 127.0.0.1:502)",
                          "cell.yaml:4:11: error[C010]: 'unit' must be 0..255",
                          "cell.yaml:5:11: error[C010]: 'poll' must be at least 1 ms",
                          "cell.yaml:6:14: error[C010]: 'on_loss' must be fault or hold, not 'ignore'",
                          "cell.yaml:8:38: error[C010]: 'Clamp.done' is written to the external PLC: map it to a coil or "
                          "holding register, not discrete",
                          "cell.yaml:10:10: error[C010]: 'until' names PLC variables, but the cell has no soft PLC ('plc: "
                          "sources')"));
}

TEST_F(ModbusSection, TheAddressIsKeptAsWrittenForMessagesAndParsedForTheBridge) {
  auto cell = loads(std::string("plc:\n  modbus: { address: 'localhost:1502' }\n") + kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->plcModbus->address, "localhost:1502");
  EXPECT_EQ(cell->plcModbus->peer.ipv4, 0x7f000001u);
  EXPECT_EQ(cell->plcModbus->peer.port, 1502);
  EXPECT_THAT(fails(std::string("plc:\n  modbus:\n    address: 'localhost:0'\n    timeout: 0.5 ms\n") + kDevices),
              ElementsAre("cell.yaml:3:14: error[C010]: 'address': port 0 cannot be connected to (expected HOST:PORT, e.g. "
                          "127.0.0.1:502)",
                          "cell.yaml:4:14: error[C010]: 'timeout' must be at least 1 ms"));
}

TEST_F(ModbusSection, WiringNeedsASoftPlc) {
  EXPECT_THAT(fails("devices:\n"
                    "  - name: Clamp\n"
                    "    type: timed\n"
                    "    commands:\n"
                    "      1: { name: Close, duration: 1 s }\n"
                    "    wiring: MAIN.Clamp\n"),
              ElementsAre("cell.yaml:6:13: error[C030]: 'wiring' connects ports to PLC variables, but the cell has no soft PLC "
                          "('plc: sources') and no ADS or OPC UA PLC ('plc: ads', 'plc: opcua'); a Modbus PLC reaches the signals through its map"));
}

TEST_F(ModbusSection, DetachingTheSoftPlcDropsWhatNamesItsVariables) {
  write("main.st", kMainSt);
  auto cell = loads(std::string("plc:\n  sources: [main.st]\nrun:\n  until: MAIN.count >= 3\n  record: [MAIN.count]\n") +
                    "devices:\n  - name: Clamp\n    type: timed\n" + kClampParams + "    wiring: MAIN.Clamp\n");
  ASSERT_TRUE(cell);
  EXPECT_FALSE(cell->wires.empty());
  detachSoftPlc(*cell);
  EXPECT_EQ(cell->module, nullptr);
  EXPECT_TRUE(cell->wires.empty());
  EXPECT_FALSE(cell->run.until.valid);
  EXPECT_TRUE(cell->run.recordVars.empty());
  EXPECT_EQ(busSignals(*cell).size(), 5u);
}

// `modbus: cycle_done:` publishes the soft PLC's cycle marker (`run: cycle_done`), which a Modbus
// client cannot read by name, on a tag of its own: after the map, or in the automatic one.
TEST_F(ModbusSection, TheCycleMarkerIsMappedWhereCycleDoneSays) {
  write("main.st", kMainSt);
  const std::string head = "plc:\n  sources: [main.st]\nrun:\n  cycle_done: MAIN.finished\n" + std::string(kDevices);
  auto cell = loads(head + "modbus:\n  cycle_done: { table: discrete, address: 100 }\n");
  ASSERT_TRUE(cell);
  ASSERT_NE(cell->modbus.cycleDone, kNoTag);
  EXPECT_EQ(cell->bus.name(cell->modbus.cycleDone), "MAIN.finished");
  const mb::MapEntry& marker = cell->modbus.entries.back();
  EXPECT_EQ(marker.tag, cell->modbus.cycleDone);
  EXPECT_EQ(marker.table, mb::Table::DiscreteInput);
  EXPECT_EQ(marker.address, 100);
  EXPECT_EQ(marker.dir, mb::SignalDir::Status);
  EXPECT_TRUE(marker.readOnly);
  EXPECT_TRUE(cell->modbus.automatic) << "the devices' signals keep their automatic places";

  cell = loads(head + "modbus:\n  map:\n    - { signal: Clamp.done, table: discrete, address: 0 }\n  cycle_done: {}\n");
  ASSERT_TRUE(cell);
  EXPECT_EQ(mb::formatMapCsv(cell->modbus),
            "table,address,type,signal,direction,access,word_order,scale\n"
            "discrete,0,BOOL,Clamp.done,status,read,,\n"
            "discrete,1,BOOL,MAIN.finished,status,read,,\n");
  cell = loads(std::string("plc:\n  sources: [main.st]\n") + kDevices);
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->modbus.cycleDone, kNoTag) << "no cycle_done: no marker mapped";
}

TEST_F(ModbusSection, CycleDoneMistakesAtTheirPosition) {
  write("main.st", kMainSt);
  EXPECT_THAT(fails(std::string(kDevices) + "modbus:\n  cycle_done: { table: discrete }\n"),
              ElementsAre("cell.yaml:11:15: error[C010]: 'cycle_done' publishes the PLC's cycle marker, but the cell names none: add "
                          "'run: cycle_done: VARIABLE' (a BOOL of the soft PLC)"));
  const std::string head = "plc:\n  sources: [main.st]\nrun:\n  cycle_done: MAIN.finished\n" + std::string(kDevices);  // 1-13
  EXPECT_THAT(fails(head + "modbus:\n"                                                               // 14
                           "  map:\n"                                                                 // 15
                           "    - { signal: Clamp.done, table: discrete, address: 4 }\n"              // 16
                           "  cycle_done: { table: discrete, address: 4, colour: red }\n"),           // 17
              ElementsAre("cell.yaml:17:15: error[C010]: discrete 4 overlaps 'Clamp.done' at 4",
                          "cell.yaml:17:46: error[C011]: unknown key 'colour' in 'cycle_done' (expected one of: table, type, "
                          "word_order, scale, read_only, address)"));
  EXPECT_THAT(fails(head + "modbus:\n  cycle_done: 100\n"),
              ElementsAre("cell.yaml:15:15: error[C010]: 'cycle_done' must be a mapping of `key: value` entries"));
}

}  // namespace
}  // namespace virtcom::cell::test
