#include "proto/ads/server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <limits>

#include "core/clock.hpp"
#include "proto/ads/session.hpp"

namespace virtcom::proto::ads {

namespace {

constexpr size_t kReadChunk = 16 * 1024;
// A client that does not read its responses stops being read once this much is unsent, and is
// dropped once notifications pile up beyond kMaxQueuedBytes (AdsLib's own buffer is 4 MB).
constexpr size_t kMaxUnsentBytes = 256 * 1024;
constexpr size_t kMaxQueuedBytes = 16 * 1024 * 1024;
constexpr uint8_t kWakePublished = 2;
// Discovery requests are a few hundred bytes (names, a password); longer ones are cut and ignored.
constexpr size_t kMaxDatagram = 2048;
// Polled before the connections: the wake-up pipe, the TCP listener, the UDP socket.
constexpr size_t kFixedFds = 3;  // besides net::ServerThread::kWakeStop
// Windows FILETIME (100 ns ticks since 1601) of the Unix epoch (docs/ads.md, Device notifications).
constexpr uint64_t kFileTimeUnixEpoch = 116'444'736'000'000'000ull;

struct Connection {
  int fd = -1;
  uint32_t peer = 0;
  net::RequestBudget budget;
  Session session;
  std::vector<uint8_t> rx, tx;
};

uint64_t fileTimeNow() { return kFileTimeUnixEpoch + static_cast<uint64_t>(utcNowNs() / 100); }

// Sends what the socket takes. False: close the connection.
bool flush(Connection& c) {
  if (c.tx.empty()) return true;
  ssize_t n = ::send(c.fd, c.tx.data(), c.tx.size(), MSG_NOSIGNAL);
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.tx.erase(c.tx.begin(), c.tx.begin() + n);
  return c.tx.size() <= kMaxQueuedBytes;
}

}  // namespace

Server::Server(const ServerConfig& config, const SymbolTable& table) : config_(config), device_(table, config.device) {}

std::expected<std::unique_ptr<Server>, std::string> Server::start(const ServerConfig& config, const SymbolTable& table) {
  std::unique_ptr<Server> s(new Server(config, table));
  s->openDiscovery();
  auto started = s->io_.start(config.listen, "ADS", [server = s.get()] { server->run(); });
  if (!started) return std::unexpected(started.error());
  return s;
}

Server::~Server() {
  stop();
  if (udpFd_ >= 0) ::close(udpFd_);
}

void Server::stop() { io_.stop(); }

void Server::openDiscovery() {
  if (!config_.discoveryPort) return;
  auto bound = net::bindUdp(net::Endpoint{config_.listen.ipv4, *config_.discoveryPort});
  if (!bound) {
    discoveryProblem_ = bound.error();
    return;
  }
  udpFd_ = bound->fd;
  discovery_ = bound->bound;
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) std::strcpy(host, "virtcom");
  discoveryInfo_ = DiscoveryInfo{config_.device.netId, host, config_.routePassword};
  datagram_.resize(kMaxDatagram);
  reply_.reserve(kMaxDatagram);
}

void Server::answerDatagrams() {
  while (true) {
    sockaddr_in peer{};
    socklen_t len = sizeof peer;
    ssize_t n = ::recvfrom(udpFd_, datagram_.data(), datagram_.size(), 0, reinterpret_cast<sockaddr*>(&peer), &len);
    if (n < 0) return;  // EAGAIN: all answered (errors of a datagram socket concern one datagram)
    const uint32_t ip = ntohl(peer.sin_addr.s_addr);
    reply_.clear();
    const auto request = std::span<const uint8_t>(datagram_.data(), static_cast<size_t>(n));
    const DiscoveryAnswer answer = answerDiscovery(request, discoveryInfo_, reply_);
    // A peer off the list may only ask for a route: the password decides, as on TwinCAT.
    const bool listed = config_.peers.allows(ip);
    if (!answer || (!listed && !answer.addRoute)) continue;
    if (answer.routeAdded)
      addRoute(*answer.routeAdded, ip);
    else if (answer.addRoute)
      config_.peers.logRefusal(ip, net::Refusal::BadCredentials);
    ::sendto(udpFd_, reply_.data(), reply_.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&peer), len);
  }
}

void Server::addRoute(const AmsNetId& netId, uint32_t ipv4) {
  auto& ids = config_.allowedNetIds;
  if (!ids.empty() && std::find(ids.begin(), ids.end(), netId) == ids.end()) ids.push_back(netId);
  if (!config_.peers.allowed().empty() && !config_.peers.allows(ipv4)) config_.peers.allowed().push_back(net::Ipv4Net{ipv4});
  config_.peers.log("ads: route added for AmsNetId " + formatNetId(netId) + " at " + net::formatIpv4(ipv4));
  if (config_.onRouteAdded) config_.onRouteAdded(netId, ipv4);
}

size_t Server::applyPendingWrites(const LiveImage& live, WriteObserver* audit) {
  std::lock_guard lock(mutex_);
  WriteQueue& q = device_.pendingWrites();
  const size_t n = q.size();
  if (n) q.applyTo(live.data, device_.table().layout().inputs, live.inputImage, audit);
  q.clear();
  return n;
}

std::optional<StateRequest> Server::takeStateRequest() {
  std::lock_guard lock(mutex_);
  return device_.takeStateRequest();
}

void Server::publishSnapshot(std::span<const uint8_t> data, uint16_t adsState) {
  {
    std::lock_guard lock(mutex_);
    device_.publish(data, adsState);
  }
  if (notifications_.load(std::memory_order_relaxed) > 0) io_.wake(kWakePublished);
}

void Server::run() {
  std::vector<std::unique_ptr<Connection>> clients;
  std::vector<pollfd> fds;
  std::array<uint8_t, kReadChunk> chunk;
  // Answers every whole frame in c.rx. False: close the connection.
  auto receive = [&](Connection& c) {
    ssize_t n = ::recv(c.fd, chunk.data(), chunk.size(), 0);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    c.rx.insert(c.rx.end(), chunk.begin(), chunk.begin() + n);
    size_t used = 0;
    bool keep = true;
    std::lock_guard lock(mutex_);
    while (keep) {
      auto rest = std::span<const uint8_t>(c.rx).subspan(used);
      FrameScan scan = scanFrame(rest, config_.maxFrameBytes);
      if (scan.status == FrameStatus::Malformed) return false;
      if (scan.status == FrameStatus::NeedMore) break;
      keep = c.session.handleFrame(rest.first(scan.size), c.tx, c.budget.take(monotonicNowNs()));
      used += scan.size;
    }
    c.rx.erase(c.rx.begin(), c.rx.begin() + static_cast<ptrdiff_t>(used));
    c.session.sendDueNotifications(monotonicNowNs(), fileTimeNow(), c.tx);
    return keep;
  };
  auto closeConnection = [&](Connection& c) {
    ::close(c.fd);
    c.fd = -1;
    std::lock_guard lock(mutex_);
    c.session.end();
  };
  auto countNotifications = [&] {
    size_t total = 0;
    for (const auto& c : clients) total += c->session.notificationCount();
    notifications_.store(total, std::memory_order_relaxed);
  };
  try {
    while (true) {
      fds.clear();
      fds.push_back({io_.wakeFd(), POLLIN, 0});
      fds.push_back({io_.listenFd(), POLLIN, 0});
      fds.push_back({udpFd_, POLLIN, 0});  // a negative fd is ignored by poll
      int64_t nextDue = std::numeric_limits<int64_t>::max();
      for (const auto& c : clients) {
        short events = c->tx.size() < kMaxUnsentBytes ? POLLIN : 0;
        if (!c->tx.empty()) events = static_cast<short>(events | POLLOUT);
        fds.push_back({c->fd, events, 0});
        nextDue = std::min(nextDue, c->session.nextCycleDueNs());
      }
      int timeoutMs = -1;
      if (nextDue != std::numeric_limits<int64_t>::max())
        timeoutMs = static_cast<int>(std::clamp<int64_t>((nextDue - monotonicNowNs() + 999'999) / 1'000'000, 0, 1000));
      if (::poll(fds.data(), fds.size(), timeoutMs) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      // A publish only needs the loop to run once: every session's notifications are due-checked below.
      if ((fds[0].revents & POLLIN) && io_.takeStopRequest()) break;
      if (fds[2].revents & POLLIN) answerDatagrams();
      for (size_t i = 0; i < clients.size(); ++i) {
        if ((fds[i + kFixedFds].revents & (POLLIN | POLLHUP | POLLERR)) && !receive(*clients[i])) closeConnection(*clients[i]);
      }
      // Before anything is sent: a client that got its AddNotification reply may make the scan
      // publish at once, and that publish must wake this thread.
      countNotifications();
      for (auto& c : clients) {
        if (c->fd < 0) continue;
        if (c->session.notificationCount() > 0) {
          std::lock_guard lock(mutex_);
          c->session.sendDueNotifications(monotonicNowNs(), fileTimeNow(), c->tx);
        }
        if (!flush(*c)) closeConnection(*c);
      }
      std::erase_if(clients, [](const auto& c) { return c->fd < 0; });
      if (fds[1].revents & POLLIN) {
        uint32_t peer = 0;
        int fd = io_.acceptClient(config_.peers, clients.size(), [&](uint32_t ip) {
          return static_cast<size_t>(std::ranges::count_if(clients, [ip](const auto& c) { return c->peer == ip; }));
        }, peer);
        if (fd >= 0) {
          clients.push_back(std::make_unique<Connection>(Connection{
              fd, peer, net::RequestBudget(config_.peers.limits().requestsPerSecond), Session(device_, config_.allowedNetIds), {}, {}}));
          clients.back()->session.setPeer(peer, net::ServerThread::peerPort(fd));
        }
      }
      connections_.store(clients.size());
    }
  } catch (const std::bad_alloc&) {
    // Out of memory on the I/O side: stop serving; the PLC keeps running.
  }
  for (auto& c : clients) ::close(c->fd);
  connections_.store(0);
}

}  // namespace virtcom::proto::ads
