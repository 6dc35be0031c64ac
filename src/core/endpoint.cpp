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

TextResult<std::vector<uint32_t>> parseAllowList(std::string_view text) {
  std::vector<uint32_t> out;
  while (!text.empty()) {
    auto comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    if (!item.empty()) {
      auto ip = parseIpv4(item);
      if (!ip) return TextResult<std::vector<uint32_t>>::failure(ip.error());
      out.push_back(*ip);
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (out.empty()) return TextResult<std::vector<uint32_t>>::failure(std::string("the allow-list names no address"));
  return out;
}

std::string formatEndpoint(const Endpoint& e) { return formatIpv4(e.ipv4) + ":" + std::to_string(e.port); }

}  // namespace virtcom
