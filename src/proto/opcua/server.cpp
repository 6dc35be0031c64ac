#include "proto/opcua/server.hpp"

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cerrno>
#include <iostream>

#include "core/clock.hpp"
#include "proto/opcua/channel.hpp"
#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr size_t kReadChunk = 16 * 1024;
// A client that does not read its responses stops being read once this much is unsent.
constexpr size_t kMaxUnsentBytes = 1024 * 1024;
constexpr size_t kFixedFds = 2;  // the wake-up pipe, the listener

struct Connection {
  int fd = -1;
  uint32_t peer = 0;  // IPv4
  Channel channel;
  std::vector<uint8_t> rx, tx;
  bool closing = false;  // answered; closed once tx is sent
  ExternalWriter writer;  // who its writes are audited as
};

// Sends what the socket takes. False: close the connection.
bool flush(Connection& c) {
  if (c.tx.empty()) return !c.closing;
  ssize_t n = ::send(c.fd, c.tx.data(), c.tx.size(), MSG_NOSIGNAL);
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.tx.erase(c.tx.begin(), c.tx.begin() + n);
  return !(c.closing && c.tx.empty());
}

}  // namespace

Server::Server(const ServerConfig& config, const ads::SymbolTable& table) : config_(config), table_(table), core_(table, config) {}

std::expected<std::unique_ptr<Server>, std::string> Server::start(const ServerConfig& config, const ads::SymbolTable& table) {
  std::unique_ptr<Server> s(new Server(config, table));
  auto started = s->io_.start(config.listen, "OPC UA", [server = s.get()] { server->run(); });
  if (!started) return std::unexpected(started.error());
  std::lock_guard lock(s->mutex_);
  s->core_.setBound(s->io_.bound());
  return s;
}

Server::~Server() { stop(); }

std::string Server::endpointUrl() {
  std::lock_guard lock(mutex_);
  return core_.endpointUrl();
}

size_t Server::applyPendingWrites(const LiveImage& live, WriteObserver* audit) {
  std::lock_guard lock(mutex_);
  ads::WriteQueue& q = core_.pendingWrites();
  const size_t n = q.size();
  if (n) q.applyTo(live.data, table_.layout().inputs, live.inputImage, audit);
  q.clear();
  return n;
}

void Server::publishSnapshot(std::span<const uint8_t> data, std::span<const uint8_t> extra) {
  std::lock_guard lock(mutex_);
  core_.publish(data, extra);
}

void Server::run() {
  std::vector<std::unique_ptr<Connection>> clients;
  std::vector<pollfd> fds;
  std::array<uint8_t, kReadChunk> chunk;
  const size_t maxFrame = std::max<size_t>(config_.receiveBufferBytes, kMinBufferSize);
  // Answers every whole message in c.rx. False: close the connection now.
  auto receive = [&](Connection& c) {
    ssize_t n = ::recv(c.fd, chunk.data(), chunk.size(), 0);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    c.rx.insert(c.rx.end(), chunk.begin(), chunk.begin() + n);
    size_t used = 0;
    std::lock_guard lock(mutex_);
    core_.pendingWrites().setWriter(c.writer);
    while (!c.closing) {
      auto rest = std::span<const uint8_t>(c.rx).subspan(used);
      FrameScan scan = scanFrame(rest, maxFrame);
      if (scan.status == FrameStatus::NeedMore) break;
      if (scan.status == FrameStatus::Malformed) {
        Writer w(c.tx);
        writeError(w, static_cast<uint32_t>(StatusCodeValue::BadTcpMessageTooLarge), "message size out of range");
        c.closing = true;
        break;
      }
      c.closing = !c.channel.handleFrame(rest.first(scan.size), c.tx, monotonicNowNs());
      // The operator learns why a client was refused and how to trust it; the client does not.
      if (c.closing && !c.channel.rejection().empty())
        std::cerr << "opcua: " + net::formatIpv4(c.peer) + ": " + c.channel.rejection() + "\n";
      used += scan.size;
    }
    c.rx.erase(c.rx.begin(), c.rx.begin() + static_cast<ptrdiff_t>(used));
    if (!c.closing) c.channel.tick(monotonicNowNs(), c.tx);
    return true;
  };
  try {
    while (true) {
      fds.clear();
      fds.push_back({io_.wakeFd(), POLLIN, 0});
      fds.push_back({io_.listenFd(), POLLIN, 0});
      int64_t nextDue = INT64_MAX;
      {
        std::lock_guard lock(mutex_);
        for (const auto& c : clients) nextDue = std::min(nextDue, c->channel.nextDueNs());
      }
      for (const auto& c : clients) {
        short events = c->tx.size() < kMaxUnsentBytes && !c->closing ? POLLIN : 0;
        if (!c->tx.empty()) events = static_cast<short>(events | POLLOUT);
        fds.push_back({c->fd, events, 0});
      }
      int timeoutMs = -1;
      if (nextDue != INT64_MAX)
        timeoutMs = static_cast<int>(std::clamp<int64_t>((nextDue - monotonicNowNs() + 999'999) / 1'000'000, 0, 1000));
      if (::poll(fds.data(), fds.size(), timeoutMs) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      if ((fds[0].revents & POLLIN) && io_.takeStopRequest()) break;
      for (size_t i = 0; i < clients.size(); ++i) {
        Connection& c = *clients[i];
        bool keep = true;
        if (fds[i + kFixedFds].revents & (POLLIN | POLLHUP | POLLERR)) keep = receive(c);
        if (keep && !c.closing) {
          std::lock_guard lock(mutex_);
          c.channel.tick(monotonicNowNs(), c.tx);
        }
        if (keep) keep = flush(c);
        if (!keep) {
          ::close(c.fd);
          c.fd = -1;
        }
      }
      std::erase_if(clients, [](const auto& c) { return c->fd < 0; });
      if (fds[1].revents & POLLIN) {
        uint32_t peer = 0;
        int fd = io_.acceptClient(config_.peers, clients.size(), [&](uint32_t ip) {
          return static_cast<size_t>(std::ranges::count_if(clients, [ip](const auto& c) { return c->peer == ip; }));
        }, peer);
        if (fd >= 0)
          clients.push_back(std::make_unique<Connection>(Connection{
              fd, peer, Channel(core_), {}, {}, false, ExternalWriter{WriteProtocol::OpcUa, peer, net::ServerThread::peerPort(fd)}}));
      }
      connections_.store(clients.size());
    }
  } catch (const std::bad_alloc&) {
    // Out of memory on the I/O side: stop serving; the PLC keeps running.
  }
  for (auto& c : clients) ::close(c->fd);
  connections_.store(0);
}

}  // namespace virtcom::proto::opcua
