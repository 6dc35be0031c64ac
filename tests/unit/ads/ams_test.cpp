// AMS/TCP framing, the AMS header and NetIds (docs/ads.md, Wire reference: AMS/TCP and the AMS header).
#include "proto/ads/ams.hpp"

#include <gtest/gtest.h>

#include "ads_test_support.hpp"
#include "proto/ads/write_queue.hpp"

namespace virtcom::proto::ads {
namespace {

using namespace testing;

TEST(AmsFrame, ScanNeedsTheWholeFrame) {
  Bytes frame = amsRequest(851, 4, {});
  for (size_t n = 0; n < frame.size(); ++n)
    EXPECT_EQ(scanFrame(std::span(frame).first(n), 1024).status, FrameStatus::NeedMore) << n;
  FrameScan scan = scanFrame(frame, 1024);
  EXPECT_EQ(scan.status, FrameStatus::Complete);
  EXPECT_EQ(scan.size, kFrameHeaderSize);
  frame.push_back(0xAA);  // the start of the next frame stays unread
  EXPECT_EQ(scanFrame(frame, 1024).size, kFrameHeaderSize);
}

TEST(AmsFrame, MalformedFrames) {
  EXPECT_EQ(scanFrame(Bytes{0, 0, 0, 0, 1, 0}, 1024).status, FrameStatus::Malformed);  // above the limit
  EXPECT_EQ(scanFrame(Bytes{0, 0, 31, 0, 0, 0}, 1024).status, FrameStatus::Malformed);  // shorter than an AMS header
  Bytes frame = amsRequest(851, 2, u32s({0x4040, 0, 2}));
  frame[26] = 11;  // AMS data length 11, AMS/TCP says 12
  EXPECT_EQ(scanFrame(frame, 1024).status, FrameStatus::Malformed);
  EXPECT_EQ(scanFrame(Bytes{0x00, 0x10, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00}, 1024).status, FrameStatus::Complete);
}

TEST(AmsFrame, HeaderRoundTrip) {
  Bytes frame = amsRequest(851, 9, {1, 2, 3}, 0x01020304);
  auto h = readAmsHeader(frame);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->target, (AmsAddress{kLocalAliasNetId, 851}));
  EXPECT_EQ(h->source, (AmsAddress{kClientNetId, 30000}));
  EXPECT_EQ(h->commandId, 9);
  EXPECT_EQ(h->dataLength, 3u);
  EXPECT_EQ(h->invokeId, 0x01020304u);
  EXPECT_FALSE(readAmsHeader(std::span(frame).first(37)));
  AmsHeader r = responseHeader(*h, 8, 6);
  EXPECT_EQ(r.target, h->source);
  EXPECT_EQ(r.source, h->target);
  EXPECT_EQ(r.stateFlags, 0x0005);
  EXPECT_EQ(r.errorCode, 6u);
  EXPECT_EQ(r.invokeId, h->invokeId);
}

TEST(AmsNetIdText, ParseAndFormat) {
  EXPECT_EQ(parseNetId("192.168.0.1.1.1"), (AmsNetId{192, 168, 0, 1, 1, 1}));
  EXPECT_EQ(formatNetId({5, 80, 201, 232, 1, 1}), "5.80.201.232.1.1");
  for (const char* bad : {"", "1.2.3.4.5", "1.2.3.4.5.6.7", "1.2.3.4.5.256", "1.2.3.4.5.x", "1..2.3.4.5", "1.2.3.4.5.6."})
    EXPECT_FALSE(parseNetId(bad)) << bad;
}

TEST(AdsErrorText, NamesTheCodes) {
  EXPECT_STREQ(errorText(0x710), "symbol not found");
  EXPECT_STREQ(errorText(0x12345), "ADS error");
}

TEST(AdsWriteQueue, AppliesInOrderAndMirrorsInputs) {
  WriteQueue q(16);
  Bytes a{1, 2}, b{3}, bit{1};
  q.push(4, a);
  q.push(5, b);
  q.push(6, bit, 0x10);
  EXPECT_FALSE(q.hasRoom(14));
  Bytes image(8, 0), inputs(2, 0);
  q.applyTo(image, ByteRange{5, 2}, inputs);
  EXPECT_EQ(image, (Bytes{0, 0, 0, 0, 1, 3, 0x10, 0}));
  EXPECT_EQ(inputs, (Bytes{3, 0x10}));
  q.clear();
  EXPECT_TRUE(q.empty());
  EXPECT_TRUE(q.hasRoom(16));
}

}  // namespace
}  // namespace virtcom::proto::ads
