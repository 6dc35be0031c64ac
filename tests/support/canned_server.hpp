#pragma once
// Test-only: a server on 127.0.0.1 whose every answer is given in advance. Its first connection
// is sent the whole stream; then it closes its sending side and swallows what it is sent until
// the client closes. For the protocol clients' tests and fuzz targets: what a client makes of a
// server's bytes, whatever it asks. Accept gives up after 2 s, so the destructor never hangs.
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdint>
#include <span>
#include <thread>
#include <vector>

namespace virtcom::test {

class CannedServer {
 public:
  explicit CannedServer(std::span<const uint8_t> stream) : stream_(stream.begin(), stream.end()) {
    listenFd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    timeval wait{2, 0};
    ::setsockopt(listenFd_, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof addr;
    if (::bind(listenFd_, reinterpret_cast<sockaddr*>(&addr), size) == 0 && ::listen(listenFd_, 1) == 0 &&
        ::getsockname(listenFd_, reinterpret_cast<sockaddr*>(&addr), &size) == 0)
      port_ = ntohs(addr.sin_port);
    if (port_ != 0) thread_ = std::thread([this] { serve(); });
  }
  ~CannedServer() {
    if (thread_.joinable()) thread_.join();
    ::close(listenFd_);
  }
  CannedServer(const CannedServer&) = delete;
  CannedServer& operator=(const CannedServer&) = delete;

  // The listening port; 0 if it could not listen.
  uint16_t port() const { return port_; }

 private:
  void serve() {
    const int fd = ::accept(listenFd_, nullptr, nullptr);
    if (fd < 0) return;
    std::span<const uint8_t> rest(stream_);
    while (!rest.empty()) {
      const ssize_t n = ::send(fd, rest.data(), rest.size(), MSG_NOSIGNAL);
      if (n <= 0) break;
      rest = rest.subspan(static_cast<size_t>(n));
    }
    ::shutdown(fd, SHUT_WR);
    char sink[4096];
    while (::recv(fd, sink, sizeof sink, 0) > 0) {
    }
    ::close(fd);
  }

  std::vector<uint8_t> stream_;
  int listenFd_ = -1;
  uint16_t port_ = 0;
  std::thread thread_;
};

}  // namespace virtcom::test
