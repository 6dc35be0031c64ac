#include "proto/net/endpoint.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace virtcom::proto::net {

std::expected<uint32_t, std::string> parseIpv4(std::string_view text) {
  std::string host(text);
  if (host == "localhost") host = "127.0.0.1";
  in_addr addr{};
  if (::inet_pton(AF_INET, host.c_str(), &addr) != 1) return std::unexpected("'" + std::string(text) + "' is not an IPv4 address");
  return ntohl(addr.s_addr);
}

std::string formatIpv4(uint32_t ipv4) {
  in_addr addr{htonl(ipv4)};
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &addr, text, sizeof text);
  return text;
}

std::string errnoText(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

bool setNonBlocking(int fd) {
  int flags = ::fcntl(fd, F_GETFL);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

std::expected<Endpoint, std::string> parseEndpoint(std::string_view text) {
  auto colon = text.rfind(':');
  if (colon == std::string_view::npos) return std::unexpected("expected HOST:PORT, found '" + std::string(text) + "'");
  auto ip = parseIpv4(text.substr(0, colon));
  if (!ip) return std::unexpected(ip.error());
  std::string_view portText = text.substr(colon + 1);
  unsigned port = 0;
  auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), port);
  if (ec != std::errc{} || end != portText.data() + portText.size() || port > 65535 || portText.empty())
    return std::unexpected("'" + std::string(portText) + "' is not a port number (0-65535)");
  return Endpoint{*ip, static_cast<uint16_t>(port)};
}

std::expected<std::vector<uint32_t>, std::string> parseAllowList(std::string_view text) {
  std::vector<uint32_t> out;
  while (!text.empty()) {
    auto comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    if (!item.empty()) {
      auto ip = parseIpv4(item);
      if (!ip) return std::unexpected(ip.error());
      out.push_back(*ip);
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (out.empty()) return std::unexpected(std::string("the allow-list names no address"));
  return out;
}

std::string formatEndpoint(const Endpoint& e) { return formatIpv4(e.ipv4) + ":" + std::to_string(e.port); }

std::expected<Listener, std::string> listenTcp(const Endpoint& at, int backlog) {
  int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return std::unexpected(errnoText("socket"));
  auto fail = [fd](std::string text) {
    ::close(fd);
    return std::unexpected(std::move(text));
  };
  int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(at.port);
  addr.sin_addr.s_addr = htonl(at.ipv4);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    return fail(errnoText(("cannot bind " + formatEndpoint(at)).c_str()));
  if (::listen(fd, backlog) != 0 || !setNonBlocking(fd)) return fail(errnoText("listen"));
  socklen_t len = sizeof addr;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) return fail(errnoText("getsockname"));
  return Listener{fd, Endpoint{at.ipv4, ntohs(addr.sin_port)}};
}

int acceptPeer(int listenFd, uint32_t& peerIpv4) {
  sockaddr_in peer{};
  socklen_t len = sizeof peer;
  int fd = ::accept4(listenFd, reinterpret_cast<sockaddr*>(&peer), &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd >= 0) peerIpv4 = ntohl(peer.sin_addr.s_addr);
  return fd;
}

}  // namespace virtcom::proto::net
