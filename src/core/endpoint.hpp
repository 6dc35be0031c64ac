#pragma once
// TCP endpoint and IPv4 address text ("HOST:PORT", allow-lists), below every layer that names a
// peer: the cell file's external PLCs and the protocol servers' listen options read the same
// text with the same messages. Text only: sockets live in proto/net.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/text_result.hpp"

namespace virtcom {

struct Endpoint {
  uint32_t ipv4 = 0x7f000001;  // host byte order
  uint16_t port = 0;
};
// "HOST:PORT" with an IPv4 address or "localhost"; port 0 picks a free port. Error text on failure.
TextResult<Endpoint> parseEndpoint(std::string_view text);
// An IPv4 address (or "localhost") in host byte order. Error text on failure.
TextResult<uint32_t> parseIpv4(std::string_view text);
// "ADDR,ADDR,..." of IPv4 peer addresses (host byte order). Error text on failure.
TextResult<std::vector<uint32_t>> parseAllowList(std::string_view text);
std::string formatIpv4(uint32_t ipv4);
std::string formatEndpoint(const Endpoint& e);

}  // namespace virtcom
