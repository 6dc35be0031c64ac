// Where TwinCAT's answers differ from a strict reading of the protocol and the common clients
// rely on it (issue 16): reads longer than the symbol, handles per AMS route, the first sample
// of a notification. Driven through Session without sockets.
#include <gtest/gtest.h>

#include "ads_test_support.hpp"
#include "proto/ads/session.hpp"

namespace virtcom::proto::ads {
namespace {

using namespace testing;

class FidelityTest : public ::testing::Test {
 protected:
  FidelityTest() {
    Bytes image(64, 0);
    image[16] = 0x01, image[17] = 0x02, image[18] = 0x03, image[19] = 0x04;  // %I
    image[24] = 0x11, image[31] = 0x99;                                       // %M
    image[32] = 0x2a;                                                         // MAIN.count = 42
    image[36] = 0x67, image[37] = 0x12;                                       // MAIN.serial = 4711
    device.publish(image, kAdsStateRun);
  }

  // The ADS data of `session`'s answer to one request from source port `sourcePort`.
  Bytes call(Session& s, Command command, const Bytes& data, uint16_t sourcePort = 30000) {
    Bytes out;
    EXPECT_TRUE(s.handleFrame(amsRequest(kPlcPort, static_cast<uint16_t>(command), data, 5, kLocalAliasNetId, sourcePort), out));
    return out.size() < kFrameHeaderSize ? Bytes{} : Bytes(out.begin() + kFrameHeaderSize, out.end());
  }
  Bytes handleOf(Session& s, const std::string& name, uint16_t sourcePort = 30000) {
    return call(s, Command::ReadWrite, u32s({0xF003, 0, 4, static_cast<uint32_t>(name.size())}, text(name, false)), sourcePort);
  }

  SymbolTable table = makeTable();
  DeviceConfig config;
  Device device{table, config};
  Session session{device};
};

// pyads reads every STRING by handle with a 1024-byte buffer; TwinCAT answers the symbol's bytes
// and their length.
TEST_F(FidelityTest, ReadByHandleLongerThanTheSymbolAnswersTheSymbol) {
  EXPECT_EQ(hex(handleOf(session, "MAIN.count")), "00 00 00 00 04 00 00 00 01 00 00 00");
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0xF005, 1, 1024}))), "00 00 00 00 02 00 00 00 2a 00");
  EXPECT_EQ(hex(call(session, Command::ReadWrite, u32s({0xF005, 1, 1024, 0}))), "00 00 00 00 02 00 00 00 2a 00");
  // A shorter read still gets the first bytes.
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0xF005, 1, 1}))), "00 00 00 00 01 00 00 00 2a");
}

TEST_F(FidelityTest, ReadByNameLongerThanTheSymbolAnswersTheSymbol) {
  EXPECT_EQ(hex(call(session, Command::ReadWrite, u32s({0xF004, 0, 1024, 10}, text("MAIN.count", false)))),
            "00 00 00 00 02 00 00 00 2a 00");
}

TEST_F(FidelityTest, AreaReadsPastTheEndAnswerWhatThereIs) {
  // %M is 8 bytes (24..31): 16 asked at offset 4 gives 4; %MX from bit 60 gives 4 bits.
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0x4020, 4, 16}))), "00 00 00 00 04 00 00 00 00 00 00 99");
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0x4021, 60, 16}))), "00 00 00 00 04 00 00 00 01 00 00 01");
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0xF020, 0, 1024}))), "00 00 00 00 04 00 00 00 01 02 03 04");
  // An offset beyond the area is still an error.
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0x4020, 9, 1}))), "03 07 00 00 00 00 00 00");
}

TEST_F(FidelityTest, SumReadItemLongerThanItsSymbolIsPaddedToItsSlot) {
  EXPECT_EQ(hex(handleOf(session, "MAIN.count")), "00 00 00 00 04 00 00 00 01 00 00 00");
  // Two items: by handle (4 asked, 2 there) and MAIN.serial by group (4): slots stay where asked.
  Bytes reply = call(session, Command::ReadWrite, u32s({0xF080, 2, 16, 24}, u32s({0xF005, 1, 4, 0x4040, 36, 4})));
  EXPECT_EQ(hex(reply), "00 00 00 00 10 00 00 00 00 00 00 00 00 00 00 00 2a 00 00 00 67 12 00 00");
}

// Beckhoff's adstool test creates a handle in one process and uses it from the next: TwinCAT
// keeps handles per AMS route (NetId and port), not per connection.
TEST_F(FidelityTest, HandlesOutliveTheConnectionOnTheSameRoute) {
  {
    Session first(device);
    EXPECT_EQ(hex(handleOf(first, "MAIN.serial")), "00 00 00 00 04 00 00 00 01 00 00 00");
  }
  Session next(device);
  EXPECT_EQ(hex(call(next, Command::Read, u32s({0xF005, 1, 4}))), "00 00 00 00 04 00 00 00 67 12 00 00");
  // Another AMS port is another route: the handle is not its.
  EXPECT_EQ(hex(call(next, Command::Read, u32s({0xF005, 1, 4}), 30001)), "10 07 00 00 00 00 00 00");
  // Released, it is gone for every connection of the route, and the route is forgotten.
  EXPECT_EQ(hex(call(next, Command::Write, u32s({0xF006, 0, 4}, u32s({1})))), "00 00 00 00");
  EXPECT_EQ(hex(call(session, Command::Read, u32s({0xF005, 1, 4}))), "10 07 00 00 00 00 00 00");
  EXPECT_EQ(device.handles().routeCount(), 0u);
}

// ads-client registers an AMS port with the server's router (AMS/TCP port connect): that port
// is the connection's, and its handles go with it.
TEST_F(FidelityTest, HandlesOfAPortRegisteredByTheConnectionEndWithIt) {
  DeviceConfig own;
  own.netId = kClientNetId;  // the router hands its own NetId to the client
  Device d(table, own);
  Session registered(d);
  Bytes out;
  ASSERT_TRUE(registered.handleFrame(Bytes{0x00, 0x10, 0x02, 0x00, 0x00, 0x00, 0x30, 0x75}, out));  // port 30000
  EXPECT_EQ(hex(handleOf(registered, "MAIN.count")), "00 00 00 00 04 00 00 00 01 00 00 00");
  Session ownRouter(d);  // AdsLib: its own router, port 30001
  EXPECT_EQ(hex(handleOf(ownRouter, "MAIN.count", 30001)), "00 00 00 00 04 00 00 00 01 00 00 00");
  registered.end();
  ownRouter.end();
  EXPECT_EQ(d.handles().count({kClientNetId, 30000}), 0u);
  EXPECT_EQ(d.handles().count({kClientNetId, 30001}), 1u);
}

TEST_F(FidelityTest, HandleLimitsPerRouteAndRoutes) {
  DeviceConfig small;
  small.maxHandlesPerRoute = 2;
  small.maxHandleRoutes = 2;
  Device d(table, small);
  Session s(d);
  EXPECT_EQ(hex(handleOf(s, "MAIN.count")), "00 00 00 00 04 00 00 00 01 00 00 00");
  EXPECT_EQ(hex(handleOf(s, "MAIN.count")), "00 00 00 00 04 00 00 00 02 00 00 00");
  EXPECT_EQ(hex(handleOf(s, "MAIN.count")), "0a 07 00 00 00 00 00 00");
  EXPECT_EQ(hex(handleOf(s, "MAIN.count", 30001)), "00 00 00 00 04 00 00 00 01 00 00 00");
  EXPECT_EQ(hex(handleOf(s, "MAIN.count", 30002)), "0a 07 00 00 00 00 00 00");
  // A released slot is used again.
  EXPECT_EQ(hex(call(s, Command::Write, u32s({0xF006, 0, 4}, u32s({1})))), "00 00 00 00");
  EXPECT_EQ(hex(handleOf(s, "MAIN.count")), "00 00 00 00 04 00 00 00 01 00 00 00");
}

// AdsLib registers its callback only after the AddDeviceNotification reply: a first sample in
// the reply's segment is lost. It goes out one task cycle later, as on TwinCAT.
TEST_F(FidelityTest, FirstSampleComesOneTaskCycleAfterTheReply) {
  EXPECT_EQ(hex(call(session, Command::AddDeviceNotification, u32s({0x4040, 32, 2, 4, 0, 0, 0, 0, 0, 0}))),
            "00 00 00 00 01 00 00 00");
  Bytes out;
  session.sendDueNotifications(500, 0, out);
  session.sendDueNotifications(500 + kFirstSampleDelayNs - 1, 0, out);
  EXPECT_TRUE(out.empty());
  session.sendDueNotifications(500 + kFirstSampleDelayNs, 0, out);
  ASSERT_EQ(out.size(), kFrameHeaderSize + 30);
  EXPECT_EQ(out[out.size() - 2], 0x2a);
}

}  // namespace
}  // namespace virtcom::proto::ads
