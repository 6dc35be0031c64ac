// libFuzzer target for the ADS codec: the input is a receive stream, cut into frames by
// scanFrame exactly as the server does, each answered by a Session over a small symbol table,
// with notifications evaluated after every frame. Finds out-of-bounds reads/writes and aborts in
// the AMS/TCP, AMS and ADS parsers, the sum commands and the notification code, and in the
// symbol entry parser the client bridge applies to replies (each frame's ADS data), and in the
// UDP discovery parser (the whole input as one datagram).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "proto/ads/discovery.hpp"
#include "proto/ads/entries.hpp"
#include "proto/ads/session.hpp"

namespace ads = virtcom::proto::ads;

namespace {

const ads::SymbolTable& table() {
  static const ads::SymbolTable t(
      {{"MAIN.count", "INT", 0x4040, 32, 2, ads::adst::kInt16, 0},
       {"MAIN.serial", "DINT", 0x4040, 36, 4, ads::adst::kInt32, ads::kSymbolFlagReadOnly}},
      {{"INT", "", 2, ads::adst::kInt16, ads::kTypeFlagDataType, {}, {}, {}},
       {"DINT", "", 4, ads::adst::kInt32, ads::kTypeFlagDataType, {}, {}, {}},
       {"E", "INT", 2, ads::adst::kInt16, ads::kTypeFlagDataType | ads::kTypeFlagEnumInfos, {}, {}, {{"A", 1}, {"B", -2}}},
       {"ARRAY [1..2] OF INT", "INT", 4, ads::adst::kInt16, ads::kTypeFlagDataType, {{1, 2}}, {}, {}}},
      {64, {16, 4}, {20, 4}, {24, 8}, {{36, 4}}},
      [](std::string_view path) -> std::optional<ads::Symbol> {
        if (ads::lowerCase(path) == "main.count") return ads::Symbol{"MAIN.count", "INT", 0x4040, 32, 2, ads::adst::kInt16, 0};
        if (ads::lowerCase(path) == "main.bit") return ads::Symbol{"MAIN.bit", "BOOL", 0xF021, 3, 1, ads::adst::kBit, 2};
        return std::nullopt;
      });
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ads::DeviceConfig config;
  config.maxHandlesPerRoute = 64;
  config.maxHandleRoutes = 4;
  config.maxNotificationsPerConnection = 64;
  config.writeQueueBytes = 256;
  ads::Device device(table(), config);
  ads::Session session(device);
  std::span<const uint8_t> stream(data, size);
  std::vector<uint8_t> out;
  (void)ads::answerDiscovery(stream, ads::DiscoveryInfo{{1, 2, 3, 4, 1, 1}, "fuzz", "1"}, out);
  int64_t now = 0;
  while (true) {
    ads::FrameScan scan = ads::scanFrame(stream, 64 * 1024);
    if (scan.status != ads::FrameStatus::Complete) break;
    if (scan.size > ads::kFrameHeaderSize)
      (void)ads::parseSymbolEntry(stream.subspan(ads::kFrameHeaderSize, scan.size - ads::kFrameHeaderSize));
    out.clear();
    if (!session.handleFrame(stream.first(scan.size), out)) break;
    session.sendDueNotifications(now += 1'000'000, 0, out);
    if (device.pendingWrites().size() > 32) device.pendingWrites().clear();
    stream = stream.subspan(scan.size);
  }
  return 0;
}
