#pragma once
// Listening sockets shared by the protocol servers (Modbus TCP, ADS). POSIX sockets, IPv4
// only; nothing here knows a protocol.
#include <cstdint>
#include <expected>
#include <string>

#include "core/endpoint.hpp"

namespace virtcom::proto::net {

// The endpoint text is core's (the cell file names endpoints too); named here for the servers.
using virtcom::Endpoint;
using virtcom::formatEndpoint;
using virtcom::formatIpv4;
using virtcom::parseAllowList;
using virtcom::parseEndpoint;
using virtcom::parseIpv4;

// A bound, listening, non-blocking, close-on-exec TCP socket.
struct Listener {
  int fd = -1;
  Endpoint bound;  // the real port when 0 was asked for
};
// Binds and listens on `at` (SO_REUSEADDR). Error text naming the endpoint on failure.
std::expected<Listener, std::string> listenTcp(const Endpoint& at, int backlog = 16);
// Binds a non-blocking, close-on-exec UDP socket to `at` (the ADS discovery service). Error
// text naming the endpoint on failure.
std::expected<Listener, std::string> bindUdp(const Endpoint& at);
// Accepts one pending connection as a non-blocking socket and reports the peer's IPv4 address
// (host byte order). -1 if none is pending or accept failed.
int acceptPeer(int listenFd, uint32_t& peerIpv4);

// "what: strerror(errno)".
std::string errnoText(const char* what);
bool setNonBlocking(int fd);

}  // namespace virtcom::proto::net
