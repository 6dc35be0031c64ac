#pragma once
// TCP endpoints and listening sockets shared by the protocol servers (Modbus TCP, ADS).
// POSIX sockets, IPv4 only; nothing here knows a protocol.
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

namespace virtcom::proto::net {

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

// A bound, listening, non-blocking, close-on-exec TCP socket.
struct Listener {
  int fd = -1;
  Endpoint bound;  // the real port when 0 was asked for
};
// Binds and listens on `at` (SO_REUSEADDR). Error text naming the endpoint on failure.
std::expected<Listener, std::string> listenTcp(const Endpoint& at, int backlog = 16);
// Accepts one pending connection as a non-blocking socket and reports the peer's IPv4 address
// (host byte order). -1 if none is pending or accept failed.
int acceptPeer(int listenFd, uint32_t& peerIpv4);

// "what: strerror(errno)".
std::string errnoText(const char* what);
bool setNonBlocking(int fd);

}  // namespace virtcom::proto::net
