// The UDP discovery codec (port 48899): identify and add-route replies as AdsLib
// (GetRemoteAddress, AddRemoteRoute) and pyads (adsGetNetIdForPLC, add_route_to_plc) parse them.
#include "proto/ads/discovery.hpp"

#include <gtest/gtest.h>

#include "ads_test_support.hpp"

namespace virtcom::proto::ads {
namespace {

using namespace testing;

// cookie, invoke id, service, AMS address 192.168.1.50.1.1:10000, then `tags` tags.
Bytes request(uint32_t service, uint32_t invokeId, uint32_t tags, const Bytes& tagBytes = {}) {
  Bytes r = u32s({0x71146603, invokeId, service}, {192, 168, 1, 50, 1, 1, 0x10, 0x27});
  Bytes rest = u32s({tags}, tagBytes);
  r.insert(r.end(), rest.begin(), rest.end());
  return r;
}

const DiscoveryInfo kInfo{{10, 20, 30, 40, 1, 1}, "cell-pc", "1"};

TEST(Discovery, IdentifyAnswersNetIdAndComputerName) {
  Bytes out;
  ASSERT_TRUE(answerDiscovery(request(1, 9, 0), kInfo, out));
  EXPECT_EQ(hex(out),
            "03 66 14 71 09 00 00 00 01 00 00 80 "  // cookie, invoke id echoed, service | reply
            "0a 14 1e 28 01 01 10 27 "              // our NetId, port 10000
            "01 00 00 00 05 00 08 00 63 65 6c 6c 2d 70 63 00");  // 1 tag: computer name
}

// pyads' order: route name, NetId, user, password (`password`), host.
Bytes addRouteTags(char password) {
  return {0x0c, 0, 3, 0, 'p', 'c', 0, 0x07, 0, 6, 0, 192, 168, 1, 51, 1, 1,
          0x0d, 0, 2, 0, 'a', 0, 0x02, 0, 2, 0, static_cast<uint8_t>(password), 0, 0x05, 0, 2, 0, 'h', 0};
}

TEST(Discovery, AddRouteWithThePasswordIsAcceptedForItsNetIdTag) {
  Bytes out;
  DiscoveryAnswer a = answerDiscovery(request(6, 0, 5, addRouteTags('1')), kInfo, out);
  ASSERT_TRUE(a);
  EXPECT_TRUE(a.addRoute);
  EXPECT_EQ(hex(out),
            "03 66 14 71 00 00 00 00 06 00 00 80 0a 14 1e 28 01 01 10 27 "
            "01 00 00 00 01 00 04 00 00 00 00 00");  // 32 bytes: status tag, 0
  // The NetId tag, not the sender's 192.168.1.50.1.1, is let in.
  EXPECT_EQ(a.routeAdded, (AmsNetId{192, 168, 1, 51, 1, 1}));
}

TEST(Discovery, AddRouteWithoutTheRightPasswordIsRefusedAsTwinCatDoes) {
  Bytes out;
  DiscoveryAnswer wrong = answerDiscovery(request(6, 0, 5, addRouteTags('2')), kInfo, out);
  ASSERT_TRUE(wrong);
  EXPECT_FALSE(wrong.routeAdded);
  EXPECT_EQ(out.size(), 32u);
  EXPECT_EQ(Bytes(out.end() - 4, out.end()), (Bytes{0x04, 0x07, 0, 0}));  // 0x704
  // No password configured: every add route is refused, whatever it carries.
  DiscoveryInfo none{kInfo.netId, "x", ""};
  out.clear();
  DiscoveryAnswer refused = answerDiscovery(request(6, 0, 5, addRouteTags('1')), none, out);
  EXPECT_FALSE(refused.routeAdded);
  EXPECT_EQ(Bytes(out.end() - 4, out.end()), (Bytes{0x04, 0x07, 0, 0}));
  // Without a password tag at all.
  out.clear();
  EXPECT_FALSE(answerDiscovery(request(6, 0, 1, {0x07, 0, 6, 0, 1, 2, 3, 4, 1, 1}), kInfo, out).routeAdded);
  EXPECT_EQ(Bytes(out.end() - 4, out.end()), (Bytes{0x04, 0x07, 0, 0}));
}

TEST(Discovery, IgnoresWhatIsNotARequest) {
  Bytes out;
  Bytes badCookie = request(1, 0, 0);
  badCookie[0] = 0;
  EXPECT_FALSE(answerDiscovery(badCookie, kInfo, out));
  EXPECT_FALSE(answerDiscovery(request(0x80000001, 0, 0), kInfo, out));  // a reply
  EXPECT_FALSE(answerDiscovery(request(3, 0, 0), kInfo, out));           // another service
  EXPECT_FALSE(answerDiscovery(Bytes{0x03, 0x66, 0x14}, kInfo, out));   // short
  EXPECT_TRUE(out.empty());
  // A truncated tag list still gets an answer (a refusal: no password).
  Bytes cut = request(6, 0, 5, {0x07, 0, 6, 0, 1});
  EXPECT_TRUE(answerDiscovery(cut, kInfo, out));
  EXPECT_EQ(Bytes(out.end() - 4, out.end()), (Bytes{0x04, 0x07, 0, 0}));
}

}  // namespace
}  // namespace virtcom::proto::ads
