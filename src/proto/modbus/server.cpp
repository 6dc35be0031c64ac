#include "proto/modbus/server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <system_error>

#include "proto/modbus/mbap.hpp"

namespace virtcom::proto::modbus {

namespace {

constexpr size_t kReadChunk = 4096;
// A client that does not read its responses stops being read once this much is unsent.
constexpr size_t kMaxUnsentBytes = 64 * 1024;

struct Connection {
  int fd = -1;
  std::vector<uint8_t> rx;  // received, not yet a whole frame
  std::vector<uint8_t> tx;  // responses not yet sent
};

std::expected<uint32_t, std::string> parseIpv4(std::string_view text) {
  std::string host(text);
  if (host == "localhost") host = "127.0.0.1";
  in_addr addr{};
  if (::inet_pton(AF_INET, host.c_str(), &addr) != 1) return std::unexpected("'" + std::string(text) + "' is not an IPv4 address");
  return ntohl(addr.s_addr);
}

std::string formatIpv4(uint32_t ipv4) {
  in_addr addr{htonl(ipv4)};
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &addr, text, sizeof text);
  return text;
}

std::string errnoText(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

bool setNonBlocking(int fd) {
  int flags = ::fcntl(fd, F_GETFL);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
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
    size_t size = answer(rest.first(scan.size), response);
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

std::expected<Endpoint, std::string> parseEndpoint(std::string_view text) {
  auto colon = text.rfind(':');
  if (colon == std::string_view::npos) return std::unexpected("expected HOST:PORT, found '" + std::string(text) + "'");
  auto ip = parseIpv4(text.substr(0, colon));
  if (!ip) return std::unexpected(ip.error());
  std::string_view portText = text.substr(colon + 1);
  unsigned port = 0;
  auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), port);
  if (ec != std::errc{} || end != portText.data() + portText.size() || port > 65535 || portText.empty())
    return std::unexpected("'" + std::string(portText) + "' is not a port number (0-65535)");
  return Endpoint{*ip, static_cast<uint16_t>(port)};
}

std::expected<std::vector<uint32_t>, std::string> parseAllowList(std::string_view text) {
  std::vector<uint32_t> out;
  while (!text.empty()) {
    auto comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    if (!item.empty()) {
      auto ip = parseIpv4(item);
      if (!ip) return std::unexpected(ip.error());
      out.push_back(*ip);
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (out.empty()) return std::unexpected(std::string("the allow-list names no address"));
  return out;
}

std::string formatEndpoint(const Endpoint& e) { return formatIpv4(e.ipv4) + ":" + std::to_string(e.port); }

Server::Server(const ServerConfig& config, AreaSizes sizes)
    : config_(config),
      snapshotInputs_(sizes.inputs, 0),
      snapshotOutputs_(sizes.outputs, 0),
      snapshotMemory_(sizes.memory, 0),
      snapshot_{snapshotInputs_, snapshotOutputs_, snapshotMemory_},
      pending_(config.pendingEditCapacity) {}

std::expected<std::unique_ptr<Server>, std::string> Server::start(const ServerConfig& config, AreaSizes sizes) {
  std::unique_ptr<Server> s(new Server(config, sizes));
  s->listenFd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s->listenFd_ < 0) return std::unexpected(errnoText("socket"));
  int one = 1;
  ::setsockopt(s->listenFd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(config.listen.port);
  addr.sin_addr.s_addr = htonl(config.listen.ipv4);
  if (::bind(s->listenFd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    return std::unexpected(errnoText(("cannot bind " + formatEndpoint(config.listen)).c_str()));
  if (::listen(s->listenFd_, 16) != 0 || !setNonBlocking(s->listenFd_)) return std::unexpected(errnoText("listen"));
  socklen_t len = sizeof addr;
  if (::getsockname(s->listenFd_, reinterpret_cast<sockaddr*>(&addr), &len) != 0) return std::unexpected(errnoText("getsockname"));
  s->bound_ = Endpoint{config.listen.ipv4, ntohs(addr.sin_port)};
  if (::pipe2(s->wakeFds_, O_CLOEXEC | O_NONBLOCK) != 0) return std::unexpected(errnoText("pipe"));
  try {
    s->thread_ = std::thread([server = s.get()] { server->run(); });
  } catch (const std::system_error& e) {
    return std::unexpected(std::string("cannot start the Modbus thread: ") + e.what());
  }
  return s;
}

Server::~Server() {
  stop();
  for (int fd : {listenFd_, wakeFds_[0], wakeFds_[1]})
    if (fd >= 0) ::close(fd);
}

void Server::stop() {
  if (!thread_.joinable()) return;
  uint8_t byte = 1;
  while (::write(wakeFds_[1], &byte, 1) < 0 && errno == EINTR) {
  }
  thread_.join();
}

size_t Server::applyPendingWrites(const ImageView& live) {
  std::lock_guard lock(mutex_);
  auto edits = pending_.edits();
  for (const ByteEdit& e : edits) applyEdit(e, live);
  size_t n = edits.size();
  pending_.clear();
  return n;
}

void Server::publishSnapshot(const ImageView& live) {
  std::lock_guard lock(mutex_);
  for (Area a : {Area::Inputs, Area::Outputs, Area::Memory}) {
    auto from = live.bytes(a), to = snapshot_.bytes(a);
    std::copy_n(from.begin(), std::min(from.size(), to.size()), to.begin());
  }
  for (const ByteEdit& e : pending_.edits()) applyEdit(e, snapshot_);
}

void Server::run() {
  std::vector<Connection> clients;
  std::vector<pollfd> fds;
  auto answer = [this](std::span<const uint8_t> frame, std::array<uint8_t, kMaxAduSize>& response) {
    std::lock_guard lock(mutex_);
    return handleFrame(frame, snapshot_, pending_, response);
  };
  try {
    while (true) {
      fds.clear();
      fds.push_back({wakeFds_[0], POLLIN, 0});
      fds.push_back({listenFd_, POLLIN, 0});
      for (const Connection& c : clients) {
        short events = c.tx.size() < kMaxUnsentBytes ? POLLIN : 0;
        if (!c.tx.empty()) events = static_cast<short>(events | POLLOUT);
        fds.push_back({c.fd, events, 0});
      }
      if (::poll(fds.data(), fds.size(), -1) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      if (fds[0].revents) break;  // stop()
      for (size_t i = 0; i < clients.size(); ++i) {
        short ev = fds[i + 2].revents;
        bool keep = true;
        if (ev & (POLLIN | POLLHUP | POLLERR)) keep = receive(clients[i], answer);
        if (keep && (ev & POLLOUT)) keep = send(clients[i]);
        if (!keep) {
          ::close(clients[i].fd);
          clients[i].fd = -1;
        }
      }
      std::erase_if(clients, [](const Connection& c) { return c.fd < 0; });
      if (fds[1].revents & POLLIN) {
        sockaddr_in peer{};
        socklen_t len = sizeof peer;
        int fd = ::accept4(listenFd_, reinterpret_cast<sockaddr*>(&peer), &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd >= 0) {
          const auto& allow = config_.allowedPeers;
          bool allowed = allow.empty() || std::find(allow.begin(), allow.end(), ntohl(peer.sin_addr.s_addr)) != allow.end();
          if (!allowed || clients.size() >= config_.maxClients) ::close(fd);
          else clients.push_back(Connection{fd, {}, {}});
        }
      }
    }
  } catch (const std::bad_alloc&) {
    // Out of memory on the I/O side: stop serving; the PLC keeps running.
  }
  for (Connection& c : clients) ::close(c.fd);
}

}  // namespace virtcom::proto::modbus
