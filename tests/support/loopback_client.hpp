#pragma once
// Test-only: a blocking TCP client on 127.0.0.1 for the protocol servers' tests (raw frames,
// abrupt disconnects). Receives give up after 5 s, so a server bug fails a test, never hangs it.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdint>
#include <vector>

namespace virtcom::test {

class LoopbackClient {
 public:
  explicit LoopbackClient(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~LoopbackClient() { close(); }
  LoopbackClient(const LoopbackClient&) = delete;
  LoopbackClient& operator=(const LoopbackClient&) = delete;

  bool connected() const { return connected_; }
  // False if not all of `bytes` went out.
  [[nodiscard]] bool send(const std::vector<uint8_t>& bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  // Exactly n bytes; fewer if the server closed the connection or the receive timed out.
  std::vector<uint8_t> receive(size_t n) {
    std::vector<uint8_t> out(n);
    size_t got = 0;
    while (got < n) {
      ssize_t r = ::recv(fd_, out.data() + got, n - got, 0);
      if (r <= 0) break;
      got += static_cast<size_t>(r);
    }
    out.resize(got);
    return out;
  }
  // True if the server closed the connection (before the receive timeout).
  bool closedByServer() {
    uint8_t b;
    return ::recv(fd_, &b, 1, 0) == 0;
  }
  // Leaves abruptly (no protocol-level goodbye).
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  // Leaves with a TCP reset instead of an orderly close.
  void reset() {
    linger resetOnClose{1, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_LINGER, &resetOnClose, sizeof resetOnClose);
    close();
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

}  // namespace virtcom::test
