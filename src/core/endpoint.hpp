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
// An IPv4 network: the peers whose address masked with `mask` is `address` (host byte order).
struct Ipv4Net {
  uint32_t address = 0;
  uint32_t mask = 0xffffffffu;  // a single address
  bool contains(uint32_t ipv4) const { return (ipv4 & mask) == address; }
  friend bool operator==(const Ipv4Net&, const Ipv4Net&) = default;
};
// "ADDR" (one address) or "ADDR/BITS" (CIDR, BITS 0-32; host bits must be zero). Error text on failure.
TextResult<Ipv4Net> parseIpv4Net(std::string_view text);
// "ITEM,ITEM,..." of parseIpv4Net items: the peers an allow-list lets in. Error text on failure.
TextResult<std::vector<Ipv4Net>> parseAllowList(std::string_view text);
std::string formatIpv4(uint32_t ipv4);
std::string formatEndpoint(const Endpoint& e);

}  // namespace virtcom
