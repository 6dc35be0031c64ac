#include "proto/net/endpoint.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace virtcom::proto::net {

std::string errnoText(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

bool setNonBlocking(int fd) {
  int flags = ::fcntl(fd, F_GETFL);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

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

std::expected<Listener, std::string> bindUdp(const Endpoint& at) {
  int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return std::unexpected(errnoText("socket"));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(at.port);
  addr.sin_addr.s_addr = htonl(at.ipv4);
  socklen_t len = sizeof addr;
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    std::string text = errnoText(("cannot bind UDP " + formatEndpoint(at)).c_str());
    ::close(fd);
    return std::unexpected(std::move(text));
  }
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
