#include "core/endpoint.hpp"

#include <arpa/inet.h>

#include <charconv>

namespace virtcom {

namespace {

// "'TEXT'" + tail, built by appending (GCC 12 warns falsely about "'" + std::string(...)).
std::string quotedThen(std::string_view text, const char* tail) {
  std::string out(1, '\'');
  return out.append(text).append(tail);
}

}  // namespace

TextResult<uint32_t> parseIpv4(std::string_view text) {
  std::string host(text);
  if (host == "localhost") host = "127.0.0.1";
  in_addr addr{};
  if (::inet_pton(AF_INET, host.c_str(), &addr) != 1) return TextResult<uint32_t>::failure(quotedThen(text, "' is not an IPv4 address"));
  return ntohl(addr.s_addr);
}

std::string formatIpv4(uint32_t ipv4) {
  in_addr addr{htonl(ipv4)};
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &addr, text, sizeof text);
  return text;
}

TextResult<Endpoint> parseEndpoint(std::string_view text) {
  auto colon = text.rfind(':');
  if (colon == std::string_view::npos) return TextResult<Endpoint>::failure("expected HOST:PORT, found " + quotedThen(text, "'"));
  auto ip = parseIpv4(text.substr(0, colon));
  if (!ip) return TextResult<Endpoint>::failure(ip.error());
  std::string_view portText = text.substr(colon + 1);
  unsigned port = 0;
  auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), port);
  if (ec != std::errc{} || end != portText.data() + portText.size() || port > 65535 || portText.empty())
    return TextResult<Endpoint>::failure(quotedThen(portText, "' is not a port number (0-65535)"));
  return Endpoint{*ip, static_cast<uint16_t>(port)};
}

TextResult<Ipv4Net> parseIpv4Net(std::string_view text) {
  const auto slash = text.find('/');
  auto ip = parseIpv4(text.substr(0, slash));
  if (!ip) return TextResult<Ipv4Net>::failure(ip.error() + " (expected ADDRESS or ADDRESS/BITS)");
  if (slash == std::string_view::npos) return Ipv4Net{*ip};
  std::string_view bitsText = text.substr(slash + 1);
  unsigned bits = 0;
  auto [end, ec] = std::from_chars(bitsText.data(), bitsText.data() + bitsText.size(), bits);
  if (ec != std::errc{} || end != bitsText.data() + bitsText.size() || bits > 32 || bitsText.empty())
    return TextResult<Ipv4Net>::failure(quotedThen(bitsText, "' is not a prefix length (0-32) in ").append(text));
  const uint32_t mask = bits == 0 ? 0 : ~uint32_t{0} << (32 - bits);
  if ((*ip & ~mask) != 0)
    return TextResult<Ipv4Net>::failure(quotedThen(text, "' has host bits set: the network is ") +
                                        formatIpv4(*ip & mask) + "/" + std::to_string(bits));
  return Ipv4Net{*ip, mask};
}

TextResult<std::vector<Ipv4Net>> parseAllowList(std::string_view text) {
  std::vector<Ipv4Net> out;
  while (!text.empty()) {
    auto comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    if (!item.empty()) {
      auto net = parseIpv4Net(item);
      if (!net) return TextResult<std::vector<Ipv4Net>>::failure(net.error());
      out.push_back(*net);
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (out.empty()) return TextResult<std::vector<Ipv4Net>>::failure(std::string("the allow-list names no address"));
  return out;
}

std::string formatEndpoint(const Endpoint& e) { return formatIpv4(e.ipv4) + ":" + std::to_string(e.port); }

}  // namespace virtcom
