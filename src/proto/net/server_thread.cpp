#include "proto/net/server_thread.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <system_error>

namespace virtcom::proto::net {

namespace {

// Connections waiting for accept(): room for 100 client processes starting at once (the peer
// policy's defaults admit them, docs/security.md); the kernel caps it at net.core.somaxconn.
constexpr int kListenBacklog = 128;

}  // namespace

std::expected<void, std::string> ServerThread::start(const Endpoint& at, const std::string& name,
                                                     std::function<void()> loop) {
  auto listener = listenTcp(at, kListenBacklog);
  if (!listener) return std::unexpected(listener.error());
  listenFd_ = listener->fd;
  bound_ = listener->bound;
  if (::pipe2(wakeFds_, O_CLOEXEC | O_NONBLOCK) != 0) return std::unexpected(errnoText("pipe"));
  try {
    thread_ = std::thread(std::move(loop));
  } catch (const std::system_error& e) {
    return std::unexpected("cannot start the " + name + " thread: " + e.what());
  }
  return {};
}

ServerThread::~ServerThread() {
  stop();
  for (int fd : {listenFd_, wakeFds_[0], wakeFds_[1]})
    if (fd >= 0) ::close(fd);
}

void ServerThread::wake(uint8_t why) {
  // A full pipe already holds a wake-up: dropping this one loses nothing.
  while (::write(wakeFds_[1], &why, 1) < 0 && errno == EINTR) {
  }
}

bool ServerThread::takeStopRequest() {
  uint8_t why[64];
  ssize_t n = ::read(wakeFds_[0], why, sizeof why);
  return n > 0 && std::find(why, why + n, kWakeStop) != why + n;
}

int ServerThread::acceptClient(const PeerPolicy& policy, size_t open, const std::function<size_t(uint32_t)>& openFrom,
                               uint32_t& peer) {
  int fd = acceptPeer(listenFd_, peer);
  if (fd < 0) return -1;
  if (policy.admit(peer, open, openFrom(peer)) != Refusal::None) {
    ::close(fd);
    return -1;
  }
  int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  ::setsockopt(fd, SOL_SOCKET, SO_KEEPALIVE, &one, sizeof one);
  return fd;
}

uint16_t ServerThread::peerPort(int fd) {
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0 || addr.sin_family != AF_INET) return 0;
  return ntohs(addr.sin_port);
}

void ServerThread::stop() {
  if (!thread_.joinable()) return;
  wake(kWakeStop);
  thread_.join();
}

}  // namespace virtcom::proto::net
