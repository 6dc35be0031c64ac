#include "proto/modbus/server.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

#include "core/clock.hpp"
#include "proto/modbus/mbap.hpp"

namespace virtcom::proto::modbus {

namespace {

constexpr size_t kReadChunk = 4096;
// A client that does not read its responses stops being read once this much is unsent.
constexpr size_t kMaxUnsentBytes = 64 * 1024;

struct Connection {
  int fd = -1;
  uint32_t peer = 0;
  net::RequestBudget budget;
  std::vector<uint8_t> rx;  // received, not yet a whole frame
  std::vector<uint8_t> tx;  // responses not yet sent
  ExternalWriter writer;    // who its writes are audited as
};

// Exception 06 (server busy) to `frame`, a request beyond the connection's request rate.
size_t answerBusy(std::span<const uint8_t> frame, std::span<uint8_t, kMaxAduSize> response) {
  std::copy_n(frame.begin(), kMbapHeaderSize, response.begin());
  response[4] = 0;
  response[5] = 3;  // MBAP length: unit id, function | 0x80, exception code
  response[kMbapHeaderSize] = static_cast<uint8_t>(frame[kMbapHeaderSize] | 0x80);
  response[kMbapHeaderSize + 1] = static_cast<uint8_t>(ExceptionCode::ServerDeviceBusy);
  return kMbapHeaderSize + 2;
}

// Reads what is available and answers every whole frame. False: close the connection (peer
// closed, socket error, or a frame that is not Modbus TCP).
template <class Answer>
bool receive(Connection& c, Answer&& answer) {
  std::array<uint8_t, kReadChunk> chunk;
  ssize_t n = ::recv(c.fd, chunk.data(), chunk.size(), 0);
  if (n == 0) return false;
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.rx.insert(c.rx.end(), chunk.begin(), chunk.begin() + n);
  size_t used = 0;
  std::array<uint8_t, kMaxAduSize> response;
  while (true) {
    auto rest = std::span<const uint8_t>(c.rx).subspan(used);
    FrameScan scan = scanFrame(rest);
    if (scan.status == FrameStatus::Malformed) return false;
    if (scan.status == FrameStatus::NeedMore) break;
    const bool withinRate = c.budget.take(monotonicNowNs());
    size_t size = withinRate ? answer(c, rest.first(scan.size), response) : answerBusy(rest.first(scan.size), response);
    c.tx.insert(c.tx.end(), response.begin(), response.begin() + static_cast<ptrdiff_t>(size));
    used += scan.size;
  }
  c.rx.erase(c.rx.begin(), c.rx.begin() + static_cast<ptrdiff_t>(used));
  return true;
}

// Sends what the socket takes. False: close the connection.
bool send(Connection& c) {
  if (c.tx.empty()) return true;
  ssize_t n = ::send(c.fd, c.tx.data(), c.tx.size(), MSG_NOSIGNAL);
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.tx.erase(c.tx.begin(), c.tx.begin() + n);
  return true;
}

}  // namespace

Server::Server(const ServerConfig& config, ImageShape shape)
    : config_(config),
      shape_(std::move(shape)),
      snapshotInputs_(shape_.inputs, 0),
      snapshotOutputs_(shape_.outputs, 0),
      snapshotMemory_(shape_.memory, 0),
      snapshotRegisters_(shape_.registers, 0),
      snapshot_{snapshotInputs_,    snapshotOutputs_,     snapshotMemory_,
                snapshotRegisters_, shape_.layout,        shape_.readOnlyCoils,
                shape_.readOnlyHolding, shape_.writableInputs, config.readOnly},
      pending_(config.pendingEditCapacity) {}

std::expected<std::unique_ptr<Server>, std::string> Server::start(const ServerConfig& config, ImageShape shape) {
  std::unique_ptr<Server> s(new Server(config, std::move(shape)));
  auto started = s->io_.start(config.listen, "Modbus", [server = s.get()] { server->run(); });
  if (!started) return std::unexpected(started.error());
  return s;
}

Server::~Server() { stop(); }

void Server::stop() { io_.stop(); }

size_t Server::applyPendingWrites(const ImageView& live, WriteObserver* audit) {
  std::lock_guard lock(mutex_);
  pending_.applyTo(live, audit);
  size_t n = pending_.edits().size();
  pending_.clear();
  return n;
}

void Server::publishSnapshot(const ImageView& live) {
  std::lock_guard lock(mutex_);
  for (Area a : {Area::Inputs, Area::Outputs, Area::Memory, Area::Registers}) {
    auto from = live.bytes(a), to = snapshot_.bytes(a);
    std::copy_n(from.begin(), std::min(from.size(), to.size()), to.begin());
  }
  for (const ByteEdit& e : pending_.edits()) applyEdit(e, snapshot_);
}

void Server::run() {
  std::vector<Connection> clients;
  std::vector<pollfd> fds;
  auto answer = [this](const Connection& c, std::span<const uint8_t> frame, std::array<uint8_t, kMaxAduSize>& response) {
    std::lock_guard lock(mutex_);
    pending_.setWriter(c.writer);
    return handleFrame(frame, snapshot_, pending_, response);
  };
  try {
    while (true) {
      fds.clear();
      fds.push_back({io_.wakeFd(), POLLIN, 0});
      fds.push_back({io_.listenFd(), POLLIN, 0});
      for (const Connection& c : clients) {
        short events = c.tx.size() < kMaxUnsentBytes ? POLLIN : 0;
        if (!c.tx.empty()) events = static_cast<short>(events | POLLOUT);
        fds.push_back({c.fd, events, 0});
      }
      if (::poll(fds.data(), fds.size(), -1) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      if ((fds[0].revents & POLLIN) && io_.takeStopRequest()) break;
      for (size_t i = 0; i < clients.size(); ++i) {
        short ev = fds[i + 2].revents;
        bool keep = true;
        if (ev & (POLLIN | POLLHUP | POLLERR)) keep = receive(clients[i], answer);
        // Responses go out at once: the socket is nearly always writable, so waiting for POLLOUT
        // would cost every request another poll round.
        if (keep && !clients[i].tx.empty()) keep = send(clients[i]);
        if (!keep) {
          ::close(clients[i].fd);
          clients[i].fd = -1;
        }
      }
      std::erase_if(clients, [](const Connection& c) { return c.fd < 0; });
      if (fds[1].revents & POLLIN) {
        uint32_t peer = 0;
        int fd = io_.acceptClient(config_.peers, clients.size(), [&](uint32_t ip) {
          return static_cast<size_t>(std::ranges::count(clients, ip, &Connection::peer));
        }, peer);
        if (fd >= 0)
          clients.push_back(Connection{fd, peer, net::RequestBudget(config_.peers.limits().requestsPerSecond), {}, {},
                                       ExternalWriter{WriteProtocol::Modbus, peer, net::ServerThread::peerPort(fd)}});
      }
    }
  } catch (const std::bad_alloc&) {
    // Out of memory on the I/O side: stop serving; the PLC keeps running.
  }
  for (Connection& c : clients) ::close(c.fd);
}

}  // namespace virtcom::proto::modbus
