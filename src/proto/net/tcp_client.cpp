#include "proto/net/tcp_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/clock.hpp"

namespace virtcom::proto::net {

namespace {

// Waits until `fd` is ready for `events` or the deadline passes; false on timeout.
bool waitFor(int fd, short events, int64_t deadlineNs) {
  while (true) {
    int64_t leftNs = deadlineNs - monotonicNowNs();
    if (leftNs <= 0) return false;
    pollfd p{fd, events, 0};
    int r = ::poll(&p, 1, static_cast<int>((leftNs + 999'999) / 1'000'000));
    if (r > 0) return true;
    if (r < 0 && errno != EINTR) return true;  // let the next call report the error
  }
}

bool wouldBlock() { return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR; }

}  // namespace

std::expected<int, std::string> connectTcp(const Endpoint& peer, int64_t deadlineNs) {
  int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return std::unexpected(errnoText("socket"));
  auto fail = [fd](std::string why) {
    ::close(fd);
    return std::unexpected(std::move(why));
  };
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(peer.port);
  addr.sin_addr.s_addr = htonl(peer.ipv4);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    if (errno != EINPROGRESS) return fail(std::strerror(errno));
    if (!waitFor(fd, POLLOUT, deadlineNs)) return fail("no connection within the timeout");
    int error = 0;
    socklen_t len = sizeof error;
    ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len);
    if (error != 0) return fail(std::strerror(error));
  }
  int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  ::setsockopt(fd, SOL_SOCKET, SO_KEEPALIVE, &one, sizeof one);
  return fd;
}

std::expected<void, std::string> sendAll(int fd, std::span<const uint8_t> data, int64_t deadlineNs) {
  size_t sent = 0;
  while (sent < data.size()) {
    ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<size_t>(n);
    } else if (n < 0 && wouldBlock()) {
      if (!waitFor(fd, POLLOUT, deadlineNs)) return std::unexpected("no progress sending within the timeout");
    } else {
      return std::unexpected(std::strerror(errno));
    }
  }
  return {};
}

std::expected<size_t, std::string> receiveSome(int fd, std::span<uint8_t> into, int64_t deadlineNs) {
  while (true) {
    ssize_t n = ::recv(fd, into.data(), into.size(), 0);
    if (n >= 0) return static_cast<size_t>(n);
    if (!wouldBlock()) return std::unexpected(std::strerror(errno));
    if (!waitFor(fd, POLLIN, deadlineNs)) return std::unexpected("no reply within the timeout");
  }
}

}  // namespace virtcom::proto::net
