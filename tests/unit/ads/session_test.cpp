// Golden bytes for every request/response form of docs/ads.md (Wire reference) the server
// answers, driven through Session without sockets.
#include "proto/ads/session.hpp"

#include <gtest/gtest.h>

#include "ads_test_support.hpp"

namespace virtcom::proto::ads {
namespace {

using namespace testing;

class SessionTest : public ::testing::Test {
 protected:
  SessionTest() { publishImage(); }

  void publishImage() {
    Bytes image(64, 0);
    image[16] = 0x01, image[17] = 0x02, image[18] = 0x03, image[19] = 0x04;  // %I
    image[20] = 0x81;                                                         // %Q
    image[32] = 0x2a;                                                         // MAIN.count = 42
    image[36] = 0x67, image[37] = 0x12;                                       // MAIN.serial = 4711
    image[40] = 0x03, image[42] = 0xff, image[43] = 0xff;                     // MAIN.p = (3, -1)
    device.publish(image, kAdsStateRun);
  }

  // The whole response to one frame.
  Bytes exchange(const Bytes& frame) {
    Bytes out;
    EXPECT_TRUE(session.handleFrame(frame, out));
    return out;
  }

  // The ADS data of the response to (port, command, data), after checking its AMS header:
  // addresses swapped, flags 0x0005, same command and invoke id, lengths consistent.
  Bytes call(uint16_t port, Command command, const Bytes& data) {
    Bytes out = exchange(amsRequest(port, static_cast<uint16_t>(command), data, 77));
    auto h = readAmsHeader(out);
    EXPECT_TRUE(h.has_value());
    if (!h) return {};
    EXPECT_EQ(h->target, (AmsAddress{kClientNetId, 30000}));
    EXPECT_EQ(h->source, (AmsAddress{kLocalAliasNetId, port}));
    EXPECT_EQ(h->commandId, static_cast<uint16_t>(command));
    EXPECT_EQ(h->stateFlags, 0x0005);
    EXPECT_EQ(h->invokeId, 77u);
    EXPECT_EQ(h->errorCode, 0u);
    EXPECT_EQ(h->dataLength, out.size() - kFrameHeaderSize);
    return Bytes(out.begin() + kFrameHeaderSize, out.end());
  }

  Bytes readWrite(uint32_t ig, uint32_t io, uint32_t readLength, const Bytes& data) {
    return call(kPlcPort, Command::ReadWrite, u32s({ig, io, readLength, static_cast<uint32_t>(data.size())}, data));
  }

  SymbolTable table = makeTable();
  Device device{table, DeviceConfig{}};
  Session session{device};
};

TEST_F(SessionTest, PortConnectAnswersNetIdAndAPort) {
  Bytes out = exchange({0x00, 0x10, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00});
  EXPECT_EQ(hex(out), "00 10 08 00 00 00 7f 00 00 01 01 01 30 75");
  out = exchange({0x00, 0x10, 0x02, 0x00, 0x00, 0x00, 0x39, 0x30});
  EXPECT_EQ(hex(out), "00 10 08 00 00 00 7f 00 00 01 01 01 39 30");  // the requested port 12345
}

TEST_F(SessionTest, PortCloseEndsTheConnection) {
  Bytes out;
  EXPECT_FALSE(session.handleFrame(Bytes{0x01, 0x00, 0x02, 0x00, 0x00, 0x00, 0x30, 0x75}, out));
}

TEST_F(SessionTest, ReadStateResponseFrame) {
  Bytes out = exchange(amsRequest(kPlcPort, 4, {}, 7));
  EXPECT_EQ(hex(out),
            "00 00 28 00 00 00 "
            "0a 01 02 03 01 01 30 75 7f 00 00 01 01 01 53 03 "
            "04 00 05 00 08 00 00 00 00 00 00 00 07 00 00 00 "
            "00 00 00 00 05 00 00 00");
}

TEST_F(SessionTest, ARequestBeyondTheRateIsAnsweredDeviceBusy) {
  Bytes out;
  ASSERT_TRUE(session.handleFrame(amsRequest(kPlcPort, 4, {}, 7), out, false));  // ReadState
  // The fixed ReadState layout with result 0x708 (docs/security.md: --max-request-rate).
  EXPECT_EQ(hex(Bytes(out.end() - 8, out.end())), "08 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, ReadDeviceInfoNamesThePlcAndTheSystem) {
  EXPECT_EQ(hex(call(kPlcPort, Command::ReadDeviceInfo, {})),
            "00 00 00 00 03 01 b8 0f 50 6c 63 33 30 20 41 70 70 00 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kSystemPort, Command::ReadDeviceInfo, {})),
            "00 00 00 00 03 01 b8 0f 54 77 69 6e 43 41 54 20 53 79 73 74 65 6d 00 00");
}

TEST_F(SessionTest, SystemServiceState) {
  EXPECT_EQ(hex(call(kSystemPort, Command::Read, u32s({0xF0, 0, 16}))),
            "00 00 00 00 10 00 00 00 05 00 01 00 00 00 03 01 b8 0f 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kSystemPort, Command::ReadState, {})), "00 00 00 00 05 00 01 00");
  EXPECT_EQ(hex(call(kSystemPort, Command::Write, u32s({0xF0, 0, 0}))), "01 07 00 00");
}

TEST_F(SessionTest, ReadAndItsErrorForm) {
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 32, 2}))), "00 00 00 00 02 00 00 00 2a 00");
  // Errors keep result + length (ads-client and AdsLib parse 8 bytes).
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x1234, 0, 2}))), "02 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 65, 1}))), "03 07 00 00 00 00 00 00");
  // Past the area's end: what there is (docs/ads.md, Read lengths).
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 60, 8}))), "00 00 00 00 04 00 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, {0x40, 0x40})), "05 07 00 00 00 00 00 00");  // short request
}

TEST_F(SessionTest, WriteIsQueuedAndReadsBack) {
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4040, 32, 2}, {0x05, 0x01}))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 32, 2}))), "00 00 00 00 02 00 00 00 05 01");
  EXPECT_EQ(device.pendingWrites().size(), 1u);
  // A publish before the scan took the write keeps it visible.
  publishImage();
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 32, 2}))), "00 00 00 00 02 00 00 00 05 01");
  Bytes live(64, 0);
  device.pendingWrites().applyTo(live);
  EXPECT_EQ(live[32], 0x05);
  EXPECT_EQ(live[33], 0x01);
}

TEST_F(SessionTest, WriteErrors) {
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4040, 36, 4}, {1, 2, 3, 4}))), "04 07 00 00");  // read-only
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4040, 34, 4}, {1, 2, 3, 4}))), "04 07 00 00");  // overlaps it
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4040, 62, 4}, {1, 2, 3, 4}))), "05 07 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4040, 32, 4}, {1, 2}))), "05 07 00 00");  // data missing
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF00B, 0, 1}, {1}))), "01 07 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x9999, 0, 1}, {1}))), "02 07 00 00");
}

TEST_F(SessionTest, ReadOnlyServerRefusesWritesAndControl) {
  DeviceConfig config;
  config.readOnly = true;
  Device readOnly(table, config);
  Session s(readOnly);
  auto ask = [&](Command c, const Bytes& data) {
    Bytes out;
    s.handleFrame(amsRequest(kPlcPort, static_cast<uint16_t>(c), data), out);
    return hex(Bytes(out.begin() + kFrameHeaderSize, out.end()));
  };
  EXPECT_EQ(ask(Command::Write, u32s({0x4040, 32, 2}, {1, 0})), "04 07 00 00");
  EXPECT_EQ(ask(Command::WriteControl, {6, 0, 0, 0, 0, 0, 0, 0}), "04 07 00 00");
  EXPECT_EQ(ask(Command::Read, u32s({0x4040, 32, 2})), "00 00 00 00 02 00 00 00 00 00");
}

TEST_F(SessionTest, WriteQueueFullIsBusy) {
  DeviceConfig config;
  config.writeQueueBytes = 2;
  Device small(table, config);
  Session s(small);
  Bytes out;
  s.handleFrame(amsRequest(kPlcPort, 3, u32s({0x4040, 32, 2}, {1, 0})), out);
  out.clear();
  s.handleFrame(amsRequest(kPlcPort, 3, u32s({0x4040, 32, 2}, {2, 0})), out);
  EXPECT_EQ(hex(Bytes(out.begin() + kFrameHeaderSize, out.end())), "08 07 00 00");
}

TEST_F(SessionTest, WriteControlRunStop) {
  EXPECT_EQ(hex(call(kPlcPort, Command::WriteControl, {6, 0, 0, 0, 0, 0, 0, 0})), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::ReadState, {})), "00 00 00 00 06 00 00 00");
  auto request = device.takeStateRequest();
  ASSERT_TRUE(request);
  EXPECT_EQ(request->adsState, kAdsStateStop);
  EXPECT_EQ(request->writer.protocol, WriteProtocol::Ads);
  EXPECT_TRUE(request->writer.hasNetId) << "the AmsNetId of the frame that asked";
  EXPECT_EQ(hex(call(kPlcPort, Command::WriteControl, {15, 0, 0, 0, 0, 0, 0, 0})), "01 07 00 00");
}

TEST_F(SessionTest, AmsLevelErrors) {
  auto amsError = [&](const Bytes& frame) {
    Bytes out = exchange(frame);
    auto h = readAmsHeader(out);
    EXPECT_EQ(out.size(), kFrameHeaderSize);
    EXPECT_EQ(h->stateFlags, 0x0005);
    return h->errorCode;
  };
  EXPECT_EQ(amsError(amsRequest(852, 4, {})), 6u);
  EXPECT_EQ(amsError(amsRequest(kPlcPort, 4, {}, 1, AmsNetId{1, 2, 3, 4, 1, 1})), 7u);
  EXPECT_EQ(amsError(amsRequest(kPlcPort, 12, {})), 8u);
  EXPECT_EQ(amsError(amsRequest(kPlcPort, 8, {})), 8u);
}

TEST_F(SessionTest, OwnNetIdIsAcceptedLikeTheAlias) {
  DeviceConfig config;
  config.netId = {192, 168, 1, 10, 1, 1};
  Device d(table, config);
  Session s(d);
  Bytes out;
  s.handleFrame(amsRequest(kPlcPort, 4, {}, 1, config.netId), out);
  EXPECT_EQ(readAmsHeader(out)->errorCode, 0u);
  EXPECT_EQ(readAmsHeader(out)->source.netId, config.netId);
}

TEST_F(SessionTest, NetIdAllowListClosesOthers) {
  Session allowOnly(device, {AmsNetId{9, 9, 9, 9, 1, 1}});
  Bytes out;
  EXPECT_FALSE(allowOnly.handleFrame(amsRequest(kPlcPort, 4, {}), out));
  Session allowClient(device, {kClientNetId});
  EXPECT_TRUE(allowClient.handleFrame(amsRequest(kPlcPort, 4, {}), out));
}

TEST_F(SessionTest, NotificationOnChangeSendsInitialSampleThenChanges) {
  // IG, IO, length, mode 4 (on change), maxDelay 0, cycle 0, 16 reserved bytes.
  Bytes add = u32s({0x4040, 32, 2, 4, 0, 0, 0, 0, 0, 0});
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, add)), "00 00 00 00 01 00 00 00");
  Bytes out;
  session.sendDueNotifications(1000, 0x01d9000000000001ull, out);
  EXPECT_TRUE(out.empty());  // not in the reply's segment: one task cycle later
  EXPECT_EQ(session.nextCycleDueNs(), 1000 + kFirstSampleDelayNs);
  session.sendDueNotifications(1000 + kFirstSampleDelayNs, 0x01d9000000000001ull, out);
  EXPECT_EQ(hex(out),
            "00 00 3e 00 00 00 "
            "0a 01 02 03 01 01 30 75 7f 00 00 01 01 01 53 03 "
            "08 00 04 00 1e 00 00 00 00 00 00 00 00 00 00 00 "
            "1a 00 00 00 01 00 00 00 01 00 00 00 00 00 d9 01 01 00 00 00 01 00 00 00 02 00 00 00 2a 00");
  out.clear();
  session.sendDueNotifications(2000 + kFirstSampleDelayNs, 0, out);
  EXPECT_TRUE(out.empty());  // unchanged
  Bytes image(64, 0);
  image[32] = 0x2b;
  device.publish(image, kAdsStateRun);
  session.sendDueNotifications(3000 + kFirstSampleDelayNs, 0, out);
  ASSERT_EQ(out.size(), kFrameHeaderSize + 30);
  EXPECT_EQ(out.back(), 0x00);
  EXPECT_EQ(out[out.size() - 2], 0x2b);
}

TEST_F(SessionTest, CyclicNotificationFollowsItsCycle) {
  // Cycle 10 ms = 100000 x 100 ns.
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, u32s({0xF020, 0, 1, 3, 0, 100000, 0, 0, 0, 0}))),
            "00 00 00 00 01 00 00 00");
  Bytes out;
  session.sendDueNotifications(0, 0, out);
  session.sendDueNotifications(kFirstSampleDelayNs, 0, out);
  EXPECT_EQ(out.size(), kFrameHeaderSize + 29);
  EXPECT_EQ(session.nextCycleDueNs(), kFirstSampleDelayNs + 10'000'000);
  out.clear();
  session.sendDueNotifications(kFirstSampleDelayNs + 5'000'000, 0, out);
  EXPECT_TRUE(out.empty());
  session.sendDueNotifications(kFirstSampleDelayNs + 10'000'000, 0, out);
  EXPECT_EQ(out.size(), kFrameHeaderSize + 29);  // the same value again: cyclic sends anyway
}

TEST_F(SessionTest, NotificationErrorsAndDelete) {
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, u32s({0x4040, 32, 2, 1, 0, 0, 0, 0, 0, 0}))),
            "13 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, u32s({0x7777, 0, 2, 4, 0, 0, 0, 0, 0, 0}))),
            "02 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, u32s({0xF100, 0, 4, 4, 0, 0, 0, 0, 0, 0}))),
            "00 00 00 00 01 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::DeleteDeviceNotification, u32s({1}))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::DeleteDeviceNotification, u32s({1}))), "14 07 00 00");
}

// Regression (fuzz_ads_frame OOM): 0xF100 takes any length >= 4 and answers 4 bytes; a
// notification asking for ~4 GB of it samples those 4 bytes instead of reserving the request.
TEST_F(SessionTest, NotificationOnAGroupAnsweringLessThanAskedSendsWhatItAnswers) {
  EXPECT_EQ(hex(call(kPlcPort, Command::AddDeviceNotification, u32s({0xF100, 0, 0xF7FFFF03, 4, 0, 0, 0, 0, 0, 0}))),
            "00 00 00 00 01 00 00 00");
  Bytes out;
  session.sendDueNotifications(0, 0, out);
  session.sendDueNotifications(kFirstSampleDelayNs, 0, out);
  EXPECT_EQ(out.size(), kFrameHeaderSize + 32);
  EXPECT_EQ(hex(Bytes(out.begin() + kFrameHeaderSize + 24, out.begin() + kFrameHeaderSize + 28)), "04 00 00 00");
}

TEST_F(SessionTest, NotificationLimitPerConnection) {
  DeviceConfig config;
  config.maxNotificationsPerConnection = 1;
  Device d(table, config);
  Session s(d);
  Bytes add = amsRequest(kPlcPort, 6, u32s({0x4040, 32, 2, 4, 0, 0, 0, 0, 0, 0}));
  Bytes out;
  s.handleFrame(add, out);
  out.clear();
  s.handleFrame(add, out);
  EXPECT_EQ(hex(Bytes(out.begin() + kFrameHeaderSize, out.end())), "16 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, HandleByNameBothForms) {
  // AdsLib: readLength 4, name without NUL.
  EXPECT_EQ(hex(readWrite(0xF003, 0, 4, text("MAIN.count", false))), "00 00 00 00 04 00 00 00 01 00 00 00");
  // ads-client: readLength 0xFFFFFFFF, name with NUL, case differs: the extended reply.
  EXPECT_EQ(hex(readWrite(0xF003, 0, 0xFFFFFFFF, text("main.COUNT"))),
            "00 00 00 00 12 00 00 00 02 00 00 00 02 00 00 00 00 00 00 00 03 00 49 4e 54 00");
  EXPECT_EQ(hex(readWrite(0xF003, 0, 4, text("MAIN.nope"))), "10 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(readWrite(0xF003, 0, 2, text("MAIN.count"))), "05 07 00 00 00 00 00 00");
  EXPECT_EQ(device.handles().count({kClientNetId, 30000}), 2u);
}

TEST_F(SessionTest, ValueByHandleAndRelease) {
  readWrite(0xF003, 0, 4, text("MAIN.p.y"));
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF005, 1, 2}))), "00 00 00 00 02 00 00 00 ff ff");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF005, 1, 2}, {0x10, 0x00}))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 42, 2}))), "00 00 00 00 02 00 00 00 10 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF006, 0, 4}, u32s({1})))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF005, 1, 2}))), "10 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF006, 0, 4}, u32s({1})))), "10 07 00 00");
}

TEST_F(SessionTest, ReadOnlyByHandleIsRefused) {
  readWrite(0xF003, 0, 4, text("MAIN.serial"));
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF005, 1, 4}, {0, 0, 0, 0}))), "04 07 00 00");
}

TEST_F(SessionTest, ValueAndInfoByName) {
  EXPECT_EQ(hex(readWrite(0xF004, 0, 0xFFFFFFFF, text("MAIN.p"))), "00 00 00 00 04 00 00 00 03 00 ff ff");
  EXPECT_EQ(hex(readWrite(0xF007, 0, 12, text("MAIN.p.y"))),
            "00 00 00 00 0c 00 00 00 40 40 00 00 2a 00 00 00 02 00 00 00");
}

TEST_F(SessionTest, SymbolInfoByNameEx) {
  EXPECT_EQ(hex(readWrite(0xF009, 0, 0xFFFFFFFF, text("MAIN.count"))),
            "00 00 00 00 30 00 00 00 "
            "30 00 00 00 40 40 00 00 20 00 00 00 02 00 00 00 02 00 00 00 00 00 00 00 0a 00 03 00 00 00 "
            "4d 41 49 4e 2e 63 6f 75 6e 74 00 49 4e 54 00 00 00 00");
  EXPECT_EQ(hex(readWrite(0xF009, 0, 16, text("MAIN.count"))), "05 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, DataTypeByNameEx) {
  EXPECT_EQ(hex(readWrite(0xF011, 0, 0xFFFFFFFF, text("st_p"))),
            "00 00 00 00 9c 00 00 00 "
            // entry: length 156, version 1, hashes 0, size 4, offset 0, ADST 65, flags 1,
            // name 4, type 0, comment 0, dims 0, sub-items 2
            "9c 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 04 00 00 00 00 00 00 00 41 00 00 00 01 00 00 00 "
            "04 00 00 00 00 00 00 00 02 00 53 54 5f 50 00 00 00 "
            // sub-item x: length 52, size 2, offset 0, ADST 2, flags 2 (DataItem), type INT
            "34 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 02 00 00 00 00 00 00 00 02 00 00 00 02 00 00 00 "
            "01 00 03 00 00 00 00 00 00 00 78 00 49 4e 54 00 00 00 00 00 "
            // sub-item y at offset 2
            "34 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 02 00 00 00 02 00 00 00 02 00 00 00 02 00 00 00 "
            "01 00 03 00 00 00 00 00 00 00 79 00 49 4e 54 00 00 00 00 00 "
            "00 00 00");
  EXPECT_EQ(hex(readWrite(0xF011, 0, 0xFFFFFFFF, text("ST_Nope"))), "10 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, UploadInfoMatchesTheUploads) {
  Bytes symbols = call(kPlcPort, Command::Read, u32s({0xF00B, 0, 0xFFFFFFFF}));
  Bytes types = call(kPlcPort, Command::Read, u32s({0xF00E, 0, 0xFFFFFFFF}));
  const uint32_t symbolLength = static_cast<uint32_t>(symbols.size() - 8), typeLength = static_cast<uint32_t>(types.size() - 8);
  EXPECT_EQ(call(kPlcPort, Command::Read, u32s({0xF00C, 0, 8})), u32s({0, 8, 3, symbolLength}));
  EXPECT_EQ(call(kPlcPort, Command::Read, u32s({0xF00F, 0, 24})), u32s({0, 24, 3, symbolLength, 3, typeLength, 0, 0}));
  Bytes v3 = call(kPlcPort, Command::Read, u32s({0xF00F, 0, 64}));
  ASSERT_EQ(v3.size(), 72u);
  EXPECT_EQ(Bytes(v3.begin(), v3.begin() + 44), u32s({0, 64, 3, symbolLength, 3, typeLength, 0, 0, 0, 65001, 2}));
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF00F, 0, 8}))), "05 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF00B, 0, 10}))), "05 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF008, 0, 1}))), "00 00 00 00 01 00 00 00 01");
}

TEST_F(SessionTest, ProcessImageGroupsAndBits) {
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF020, 0, 4}))), "00 00 00 00 04 00 00 00 01 02 03 04");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF021, 8, 2}))), "00 00 00 00 02 00 00 00 00 01");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF025, 0, 4}))), "00 00 00 00 04 00 00 00 04 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4025, 0, 4}))), "00 00 00 00 04 00 00 00 08 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0xF031, 1, 1}, {1}))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF030, 0, 1}))), "00 00 00 00 01 00 00 00 83");
  EXPECT_EQ(hex(call(kPlcPort, Command::Write, u32s({0x4020, 7, 1}, {9}))), "00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 31, 1}))), "00 00 00 00 01 00 00 00 09");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF031, 32, 1}))), "03 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0xF100, 0, 4}))), "00 00 00 00 04 00 00 00 05 00 00 00");
}

TEST_F(SessionTest, SumRead) {
  EXPECT_EQ(hex(readWrite(0xF080, 2, 12, u32s({0x4040, 32, 2, 0x1234, 0, 2}))),
            "00 00 00 00 0c 00 00 00 00 00 00 00 02 07 00 00 2a 00 00 00");
  EXPECT_EQ(hex(readWrite(0xF080, 2, 11, u32s({0x4040, 32, 2, 0x1234, 0, 2}))), "05 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(readWrite(0xF080, 3, 12, u32s({0x4040, 32, 2, 0x1234, 0, 2}))), "05 07 00 00 00 00 00 00");
}

// Regression (fuzz_ads_frame OOM): items asking for gigabytes are refused before any reply
// memory is reserved, also when the client leaves the read length open.
TEST_F(SessionTest, SumReadLongerThanTheLimitIsRefused) {
  EXPECT_EQ(hex(readWrite(0xF080, 2, 0xFFFFFFFF, u32s({0x4040, 32, 0x7FFFFFFF, 0x4040, 32, 0x7FFFFFFF}))),
            "05 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, SumWrite) {
  EXPECT_EQ(hex(readWrite(0xF081, 2, 8, u32s({0x4040, 32, 2, 0x4040, 36, 4}, {7, 0, 1, 0, 0, 0}))),
            "00 00 00 00 08 00 00 00 00 00 00 00 04 07 00 00");
  EXPECT_EQ(hex(call(kPlcPort, Command::Read, u32s({0x4040, 32, 2}))), "00 00 00 00 02 00 00 00 07 00");
}

TEST_F(SessionTest, SumReadWriteCreatesAndSumWriteReleasesHandles) {
  Bytes data = u32s({0xF003, 0, 0xFFFF, 11, 0xF003, 0, 0xFFFF, 5});
  for (uint8_t b : text("MAIN.count")) data.push_back(b);
  for (uint8_t b : text("nope")) data.push_back(b);
  EXPECT_EQ(hex(readWrite(0xF082, 2, 0xFFFFFFFF, data)),
            "00 00 00 00 22 00 00 00 "
            "00 00 00 00 12 00 00 00 10 07 00 00 00 00 00 00 "
            "01 00 00 00 02 00 00 00 00 00 00 00 03 00 49 4e 54 00");
  // ads-client deleteVariableHandleMulti: 0xF081 with 0xF006 items.
  EXPECT_EQ(hex(readWrite(0xF081, 2, 8, u32s({0xF006, 0, 4, 0xF006, 0, 4}, u32s({1, 1})))),
            "00 00 00 00 08 00 00 00 00 00 00 00 10 07 00 00");
  EXPECT_EQ(hex(readWrite(0xF082, 1, 0xFFFFFFFF, u32s({0xF080, 1, 4, 0})) ), "00 00 00 00 08 00 00 00 01 07 00 00 00 00 00 00");
}

TEST_F(SessionTest, SumNotifications) {
  Bytes add = u32s({0x4040, 32, 2, 4, 0, 0, 0, 0, 0, 0, 0x4040, 40, 4, 3, 0, 0, 0, 0, 0, 0});
  EXPECT_EQ(hex(readWrite(0xF085, 2, 16, add)), "00 00 00 00 10 00 00 00 00 00 00 00 01 00 00 00 00 00 00 00 02 00 00 00");
  EXPECT_EQ(session.notificationCount(), 2u);
  EXPECT_EQ(hex(readWrite(0xF086, 2, 8, u32s({2, 9}))), "00 00 00 00 08 00 00 00 00 00 00 00 14 07 00 00");
  EXPECT_EQ(hex(readWrite(0xF086, 0, 8, {})), "06 07 00 00 00 00 00 00");
}

}  // namespace
}  // namespace virtcom::proto::ads
