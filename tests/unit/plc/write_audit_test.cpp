// WriteAudit, the one audit of writes from outside: what a record says (times, protocol,
// peer, variable, old and new value as IEC text) for the edits the protocol servers' queues
// report as they apply them at a scan boundary.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "core/write_audit.hpp"
#include "lang/st/compiler.hpp"
#include "plc/audited_variables.hpp"
#include "plc/runtime.hpp"

namespace virtcom::plc {
namespace {

// Globals outside a named list are named after their file ("main.speed").
const char* const kProgram = R"st(
TYPE Pair : STRUCT x : INT; y : REAL; END_STRUCT END_TYPE
VAR_GLOBAL
  speed AT %MW0 : INT;
  lamp AT %QX0.3 : BOOL;
END_VAR
PROGRAM MAIN
VAR p : Pair; a : ARRAY[1..3] OF DINT; n : DINT; m : DINT; END_VAR
n := n;
END_PROGRAM
)st";

const ExternalWriter kModbusPeer{WriteProtocol::Modbus, 0x0a000005, 50123};
const ExternalWriter kAdsPeer{WriteProtocol::Ads, 0x7f000001, 40001, true, {192, 168, 1, 7, 1, 1}};

struct Audited : ::testing::Test {
  void SetUp() override {
    SourceManager sources;
    Diagnostics diags;
    module = st::compileProgram({{"main.st", kProgram}}, sources, diags);
    ASSERT_NE(module, nullptr) << diags.render(sources);
    runtime = std::make_unique<Runtime>(*module, clock);
    ASSERT_TRUE(runtime->coldStart());
    audit = std::make_unique<WriteAudit>(auditedVariables(*module), [this](const WriteRecord& r) { records.push_back(r); });
  }
  std::span<uint8_t> memory() { return {runtime->machine().memory(), module->staticSize}; }
  uint32_t addressOf(const char* name) {
    auto ref = bc::resolveVariable(*module, name);
    EXPECT_TRUE(ref) << name;
    return ref ? ref->address : 0;
  }
  // What a queue does with one edit: reports it, then lets it land.
  void edit(const ExternalWriter& w, uint32_t address, std::span<const uint8_t> bytes, uint8_t bitMask = 0) {
    audit->beforeEdit(w, memory(), 0, address, static_cast<uint32_t>(bytes.size()), bitMask);
    if (bitMask)
      memory()[address] = static_cast<uint8_t>(bytes[0] ? memory()[address] | bitMask : memory()[address] & ~bitMask);
    else
      std::memcpy(memory().data() + address, bytes.data(), bytes.size());
  }

  VirtualClock clock;
  std::unique_ptr<bc::Module> module;
  std::unique_ptr<Runtime> runtime;
  std::unique_ptr<WriteAudit> audit;
  std::vector<WriteRecord> records;
};

TEST_F(Audited, ACoilWriteNamesTheBoolItsIecAddressThePeerAndBothValues) {
  audit->setVirtualTime(120'000'000);
  const uint8_t one = 1;
  edit(kModbusPeer, module->outputs.address, {&one, 1}, 0x08);
  audit->endEdits();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].virtualNs, 120'000'000);
  EXPECT_GT(records[0].wallNs, 0);
  EXPECT_EQ(formatWriteRecord(records[0]), "modbus 10.0.0.5:50123 main.lamp (%QX0.3): FALSE -> TRUE");
  EXPECT_EQ(audit->count(WriteProtocol::Modbus), 1u);
  EXPECT_EQ(audit->total(), 1u);
}

TEST_F(Audited, TheTwoByteEditsOfOneRegisterAreOneWrite) {
  const uint8_t lo = 0x2c, hi = 0x01;  // 300
  edit(kModbusPeer, module->memory.address, {&lo, 1});
  edit(kModbusPeer, module->memory.address + 1, {&hi, 1});
  audit->endEdits();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(formatWriteRecord(records[0]), "modbus 10.0.0.5:50123 main.speed (%MW0): 0 -> 300");
}

TEST_F(Audited, AnAdsWriteNamesTheMemberOrElementItLandsInAndTheClientsNetId) {
  const float y = 2.5f;
  edit(kAdsPeer, addressOf("MAIN.p.y"), {reinterpret_cast<const uint8_t*>(&y), 4});
  const int32_t seven = 7;
  edit(kAdsPeer, addressOf("MAIN.a[2]"), {reinterpret_cast<const uint8_t*>(&seven), 4});
  audit->endEdits();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(formatWriteRecord(records[0]), "ads 127.0.0.1:40001 (AmsNetId 192.168.1.7.1.1) MAIN.p.y: 0.0 -> 2.5");
  EXPECT_EQ(formatWriteRecord(records[1]), "ads 127.0.0.1:40001 (AmsNetId 192.168.1.7.1.1) MAIN.a[2]: 0 -> 7");
}

TEST_F(Audited, OneEditOverTwoVariablesIsAWriteOfEach) {
  const uint32_t n = addressOf("MAIN.n"), m = addressOf("MAIN.m");
  ASSERT_EQ(m, n + 4);
  const int32_t both[2] = {5, -6};
  edit(kAdsPeer, n, {reinterpret_cast<const uint8_t*>(both), 8});
  audit->endEdits();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].variable, "MAIN.n");
  EXPECT_EQ(records[0].newValue, "5");
  EXPECT_EQ(records[1].variable, "MAIN.m");
  EXPECT_EQ(records[1].oldValue, "0");
  EXPECT_EQ(records[1].newValue, "-6");
}

TEST_F(Audited, TheSameVariableWrittenTwiceInOneBatchIsTwoWritesEachWithItsOldValue) {
  const int32_t first = 1, second = 2;
  const uint32_t n = addressOf("MAIN.n");
  edit(kAdsPeer, n, {reinterpret_cast<const uint8_t*>(&first), 4});
  edit(kModbusPeer, n, {reinterpret_cast<const uint8_t*>(&second), 4});
  audit->endEdits();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].oldValue + " -> " + records[0].newValue, "0 -> 1");
  EXPECT_EQ(records[1].oldValue + " -> " + records[1].newValue, "1 -> 2");
  EXPECT_EQ(audit->count(WriteProtocol::Ads), 1u);
  EXPECT_EQ(audit->count(WriteProtocol::Modbus), 1u);
}

TEST_F(Audited, BytesWhereNothingIsDeclaredAreNamedByTheirIecAddress) {
  const uint8_t b = 0xa5;
  edit(kModbusPeer, module->memory.address + 3, {&b, 1});
  audit->endEdits();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].variable, "%MB3");
  EXPECT_EQ(records[0].oldValue + " -> " + records[0].newValue, "16#00 -> 16#A5");
}

TEST_F(Audited, NoEditNoRecordAndTheTimesLineCarriesBothClocks) {
  audit->endEdits();
  EXPECT_TRUE(records.empty());
  EXPECT_EQ(audit->total(), 0u);
  WriteRecord r;
  r.virtualNs = 1'500'000'000;
  r.wallNs = 1'764'633'601'123'000'000;  // 2025-12-02T00:00:01.123Z
  r.writer = kModbusPeer;
  r.variable = "speed";
  r.oldValue = "0";
  r.newValue = "1";
  EXPECT_EQ(formatWriteRecordWithTimes(r), "1.500s 2025-12-02T00:00:01.123Z modbus 10.0.0.5:50123 speed: 0 -> 1");
}

// A client's RUN or STOP (ADS WriteControl) is a record of the PLC's state, counted with its
// protocol's writes.
TEST_F(Audited, AStateChangeIsARecordOfThePlcState) {
  audit->setVirtualTime(2'000'000'000);
  audit->stateChanged(kAdsPeer, "RUN", "STOP");
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].virtualNs, 2'000'000'000);
  EXPECT_EQ(formatWriteRecord(records[0]), "ads 127.0.0.1:40001 (AmsNetId 192.168.1.7.1.1) PLC state: RUN -> STOP");
  EXPECT_EQ(audit->count(WriteProtocol::Ads), 1u);
}

// A force from the HMI is marked as one; the same variable written and then forced by one client
// within a batch is two records (a write and a force are not the same act).
TEST_F(Audited, AForceIsMarkedAndNotMergedWithAWrite) {
  ExternalWriter http{WriteProtocol::Http, 0x7f000001, 8080};
  ExternalWriter forcing = http;
  forcing.force = true;
  const uint8_t five[4] = {5, 0, 0, 0}, six[4] = {6, 0, 0, 0};
  edit(http, addressOf("MAIN.n"), five);
  edit(forcing, addressOf("MAIN.n"), six);
  audit->endEdits();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(formatWriteRecord(records[0]), "http 127.0.0.1:8080 MAIN.n: 0 -> 5");
  EXPECT_EQ(formatWriteRecord(records[1]), "http 127.0.0.1:8080 MAIN.n: 5 -> 6 (forced)");
}

}  // namespace
}  // namespace virtcom::plc
