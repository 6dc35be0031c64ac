// libFuzzer target for the peer policy's text (docs/security.md): `--*-allow` lists of addresses
// and CIDR networks and `HOST:PORT` endpoints, which scripts and cell files pass to every
// server. Any bytes give a list or an error text; every network parsed is canonical (no host
// bits) and contains its own address.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/endpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto list = virtcom::parseAllowList(text);
  if (!list && list.error().empty()) __builtin_trap();  // a refusal always says why
  for (const virtcom::Ipv4Net& net : *list)
    if ((net.address & ~net.mask) != 0 || !net.contains(net.address)) __builtin_trap();
  auto endpoint = virtcom::parseEndpoint(text);
  if (endpoint) {  // formatting round-trips
    auto again = virtcom::parseEndpoint(virtcom::formatEndpoint(*endpoint));
    if (!again || again->ipv4 != endpoint->ipv4 || again->port != endpoint->port) __builtin_trap();
  }
  return 0;
}
