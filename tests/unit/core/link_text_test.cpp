// The endpoint and AmsNetId text that the cell file and the command-line options share: one
// parser each, whose message both quote after their own key or option name.
#include <gtest/gtest.h>

#include "core/ams_net_id.hpp"
#include "core/endpoint.hpp"

namespace virtcom {
namespace {

TEST(LinkText, AnAmsNetIdIsSixNumbers) {
  EXPECT_EQ(parseNetId("192.168.1.10.1.1"), (AmsNetId{192, 168, 1, 10, 1, 1}));
  EXPECT_EQ(formatNetId(AmsNetId{10, 0, 0, 7, 1, 1}), "10.0.0.7.1.1");
  EXPECT_EQ(parseNetId("1.2.3").error(), "'1.2.3' is not an AmsNetId (six numbers 0-255, e.g. 192.168.1.10.1.1)");
  EXPECT_FALSE(parseNetId("1.2.3.4.5.256"));
  EXPECT_FALSE(parseNetId("1.2.3.4.5.6.7"));
}

TEST(LinkText, AnEndpointIsHostColonPort) {
  auto e = parseEndpoint("localhost:502");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->ipv4, 0x7f000001u);
  EXPECT_EQ(e->port, 502);
  EXPECT_EQ(formatEndpoint(*e), "127.0.0.1:502");
  EXPECT_EQ(parseEndpoint("127.0.0.1").error(), "expected HOST:PORT, found '127.0.0.1'");
  EXPECT_EQ(parseEndpoint("127.0.0.1:70000").error(), "'70000' is not a port number (0-65535)");
  EXPECT_EQ(parseEndpoint("host:1").error(), "'host' is not an IPv4 address");
  EXPECT_EQ(parseAllowList(",").error(), "the allow-list names no address");
}

}  // namespace
}  // namespace virtcom
