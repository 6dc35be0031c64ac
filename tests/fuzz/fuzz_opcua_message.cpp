// libFuzzer target for the OPC UA codec and services: the input is (1) a receive stream, cut into
// messages by scanFrame exactly as the server does and answered by a fresh Channel (HEL, OPN,
// MSG chunks, CLO, the services a channel serves without a session), and (2) the body of a
// request to every service of services.def, run with an activated session against a small
// address space (the ADS unit tests' table shape), so every service's decoder sees it.
// Finds out-of-bounds reads, unbounded recursion and allocation, and aborts.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "proto/opcua/channel.hpp"
#include "proto/opcua/transport.hpp"

namespace ua = virtcom::proto::opcua;
namespace ads = virtcom::proto::ads;

namespace {

ads::SymbolTable makeTable() {
  std::vector<ads::Symbol> symbols = {
      {"MAIN.count", "INT", 0x4040, 32, 2, ads::adst::kInt16, 0},
      {"MAIN.name", "STRING(7)", 0x4040, 36, 8, ads::adst::kString, 0},
      {"MAIN.p", "ST_P", 0x4040, 44, 4, ads::adst::kBigType, 0},
      {"MAIN.values", "ARRAY [0..3] OF INT", 0x4040, 48, 8, ads::adst::kInt16, 0},
      {"GVL.bit", "BOOL", 0xF021, 3, 1, ads::adst::kBit, ads::kSymbolFlagBitValue},
  };
  std::vector<ads::DataType> types = {
      {"INT", "", 2, ads::adst::kInt16, ads::kTypeFlagDataType, {}, {}, {}},
      {"STRING(7)", "", 8, ads::adst::kString, ads::kTypeFlagDataType, {}, {}, {}},
      {"ST_P", "", 4, ads::adst::kBigType, ads::kTypeFlagDataType, {}, {{"x", "INT", 2, 0, ads::adst::kInt16}, {"y", "INT", 2, 2, ads::adst::kInt16}}, {}},
      {"ARRAY [0..3] OF INT", "INT", 8, ads::adst::kInt16, ads::kTypeFlagDataType, {{0, 4}}, {}, {}},
  };
  ads::MemoryLayout layout{64, {16, 4}, {20, 4}, {24, 8}, {{32, 2}}};
  return ads::SymbolTable(symbols, types, layout, [](std::string_view) { return std::nullopt; });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const ads::SymbolTable table = makeTable();
  static ua::ServerCore core(table, [] {
    ua::ServerConfig c;  // anonymous read-write (Write decoded to the end), and one user so that UserName tokens are decoded too
    c.anonymous = ua::UserAccess::Write;
    c.users.push_back(ua::makeUserAccount("op", ua::UserAccess::Write, "pw", 10'000));
    return c;
  }());
  std::span<const uint8_t> input(data, size);
  std::vector<uint8_t> tx;
  {
    ua::Channel channel(core);
    std::span<const uint8_t> stream = input;
    while (true) {
      ua::FrameScan scan = ua::scanFrame(stream, 65536);
      if (scan.status != ua::FrameStatus::Complete) break;
      tx.clear();
      if (!channel.handleFrame(stream.first(scan.size), tx, 0)) break;
      stream = stream.subspan(scan.size);
    }
  }
  // Every service on the same bytes, with a fresh activated session each time.
  for (const ua::ServiceEntry& service : ua::allServices()) {
    ua::Session* session = core.createSession(1, 10'000, "fuzz", 0);
    if (!session) break;
    session->activated = true;
    session->access = ua::UserAccess::Write;
    const uint32_t id = session->id;
    ua::ServiceContext ctx{core, 1, session, 0};
    ua::Reader in(input);
    tx.clear();
    ua::Writer out(tx);
    service.handler(ctx, in, out);
    core.closeSession(id);
  }
  if (core.pendingWrites().size() > 1000) core.pendingWrites().clear();
  return 0;
}
