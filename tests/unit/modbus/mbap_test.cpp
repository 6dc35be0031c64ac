// MBAP framing: golden frames, malformed headers, and random bytes that must never crash.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "proto/modbus/mbap.hpp"

namespace virtcom::proto::modbus {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(Mbap, AFrameIsAnsweredWithTheSameTransactionAndUnitId) {
  std::array<uint8_t, 4> in{}, out{0x34, 0x12, 0, 0}, mem{};
  EditQueue edits(8);
  Bytes request{0x00, 0x07, 0x00, 0x00, 0x00, 0x06, 0x11, 0x03, 0x00, 0x00, 0x00, 0x01};
  std::array<uint8_t, kMaxAduSize> response{};
  size_t n = handleFrame(request, {in, out, mem}, edits, response);
  EXPECT_EQ(Bytes(response.begin(), response.begin() + static_cast<ptrdiff_t>(n)),
            (Bytes{0x00, 0x07, 0x00, 0x00, 0x00, 0x05, 0x11, 0x03, 0x02, 0x12, 0x34}));
}

TEST(Mbap, AnExceptionIsFramedToo) {
  std::array<uint8_t, 4> in{}, out{}, mem{};
  EditQueue edits(8);
  Bytes request{0x12, 0x34, 0x00, 0x00, 0x00, 0x02, 0xFF, 0x42};
  std::array<uint8_t, kMaxAduSize> response{};
  size_t n = handleFrame(request, {in, out, mem}, edits, response);
  EXPECT_EQ(Bytes(response.begin(), response.begin() + static_cast<ptrdiff_t>(n)),
            (Bytes{0x12, 0x34, 0x00, 0x00, 0x00, 0x03, 0xFF, 0xC2, 0x01}));
}

TEST(Mbap, ShortHeadersAndBodiesNeedMoreBytes) {
  EXPECT_EQ(scanFrame(Bytes{}).status, FrameStatus::NeedMore);
  EXPECT_EQ(scanFrame(Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x06}).status, FrameStatus::NeedMore);
  EXPECT_EQ(scanFrame(Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00}).status, FrameStatus::NeedMore);
}

TEST(Mbap, AWrongProtocolIdIsMalformedAsSoonAsItIsSeen) {
  EXPECT_EQ(scanFrame(Bytes{0x00, 0x01, 0x00, 0x01}).status, FrameStatus::Malformed);
  EXPECT_EQ(scanFrame(Bytes{0x00, 0x01, 0x12, 0x34, 0x00, 0x06, 0x01, 0x03, 0, 0, 0, 1}).status, FrameStatus::Malformed);
}

TEST(Mbap, LengthsOutsideTwoTo254AreMalformed) {
  EXPECT_EQ(scanFrame(Bytes{0, 1, 0, 0, 0x00, 0x00, 0x01}).status, FrameStatus::Malformed);
  EXPECT_EQ(scanFrame(Bytes{0, 1, 0, 0, 0x00, 0x01, 0x01}).status, FrameStatus::Malformed);
  EXPECT_EQ(scanFrame(Bytes{0, 1, 0, 0, 0x00, 0xFF, 0x01}).status, FrameStatus::Malformed);
  EXPECT_EQ(scanFrame(Bytes{0, 1, 0, 0, 0xFF, 0xFF, 0x01}).status, FrameStatus::Malformed);
  Bytes longest(7 + 253, 0);
  longest[5] = 0xFE;
  EXPECT_EQ(scanFrame(longest).status, FrameStatus::Complete);
}

TEST(Mbap, PipelinedFramesAreFoundOneAtATime) {
  Bytes two{0, 1, 0, 0, 0, 6, 1, 0x03, 0, 0, 0, 1, 0, 2, 0, 0, 0, 6, 1, 0x04, 0, 0, 0, 1};
  FrameScan first = scanFrame(two);
  EXPECT_EQ(first.status, FrameStatus::Complete);
  EXPECT_EQ(first.size, 12u);
  EXPECT_EQ(first.header.transactionId, 1);
  FrameScan second = scanFrame(std::span<const uint8_t>(two).subspan(12));
  EXPECT_EQ(second.header.transactionId, 2);
}

TEST(Mbap, RandomBytesNeverCrashAndAlwaysGetAFramedAnswer) {
  std::array<uint8_t, 64> in{}, out{}, mem{};
  EditQueue edits(4096);
  uint32_t seed = 12345;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  for (int round = 0; round < 20000; ++round) {
    Bytes frame{0, 0, 0, 0, 0, 0, static_cast<uint8_t>(next() >> 24)};
    size_t pdu = 1 + (next() >> 8) % 40;
    for (size_t i = 0; i < pdu; ++i) frame.push_back(static_cast<uint8_t>(next() >> 16));
    frame[7] = static_cast<uint8_t>(frame[7] % 0x18);  // mostly implemented function codes
    frame[5] = static_cast<uint8_t>(pdu + 1);
    std::array<uint8_t, kMaxAduSize> response{};
    size_t n = handleFrame(frame, {in, out, mem}, edits, response);
    ASSERT_GE(n, 9u);
    EXPECT_EQ(response[5], n - 6);
    if (!edits.hasRoom(300)) edits.clear();
  }
}

}  // namespace
}  // namespace virtcom::proto::modbus
