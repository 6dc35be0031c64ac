#pragma once
// TCP endpoint and IPv4 address text ("HOST:PORT", allow-lists), below every layer that names a
// peer: the cell file's external PLCs and the protocol servers' listen options read the same
// text with the same messages. Text only: sockets live in proto/net.
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

namespace virtcom {

struct Endpoint {
  uint32_t ipv4 = 0x7f000001;  // host byte order
  uint16_t port = 0;
};
// "HOST:PORT" with an IPv4 address or "localhost"; port 0 picks a free port. Error text on failure.
std::expected<Endpoint, std::string> parseEndpoint(std::string_view text);
// An IPv4 address (or "localhost") in host byte order. Error text on failure.
std::expected<uint32_t, std::string> parseIpv4(std::string_view text);
// "ADDR,ADDR,..." of IPv4 peer addresses (host byte order). Error text on failure.
std::expected<std::vector<uint32_t>, std::string> parseAllowList(std::string_view text);
std::string formatIpv4(uint32_t ipv4);
std::string formatEndpoint(const Endpoint& e);

}  // namespace virtcom
