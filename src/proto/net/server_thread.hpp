#pragma once
// The skeleton every protocol server (Modbus TCP, ADS) shares: a listening socket, a wake-up
// pipe and the one I/O thread whose loop polls both next to its connections. stop() wakes the
// loop with kWakeStop and joins it; the loop returns once takeStopRequest() says so.
#include <cstdint>
#include <expected>
#include <functional>
#include <string>
#include <thread>

#include "proto/net/endpoint.hpp"
#include "proto/net/peer_policy.hpp"

namespace virtcom::proto::net {

class ServerThread {
 public:
  // The wake-up byte of stop(); a server may send its own bytes with wake() besides.
  static constexpr uint8_t kWakeStop = 1;

  ServerThread() = default;
  ~ServerThread();  // stop(), then closes the socket and the pipe
  ServerThread(const ServerThread&) = delete;
  ServerThread& operator=(const ServerThread&) = delete;

  // Binds and listens on `at`, opens the wake-up pipe and runs `loop` on the I/O thread. Error
  // text if the address cannot be bound or the thread cannot start (`name`: "ADS", "Modbus").
  std::expected<void, std::string> start(const Endpoint& at, const std::string& name, std::function<void()> loop);
  // Any thread: wakes the I/O thread's poll on wakeFd() with `why`.
  void wake(uint8_t why);
  // I/O thread, once wakeFd() is readable: empties the pipe; true if stop() was among the wake-ups.
  bool takeStopRequest();
  // I/O thread, once listenFd() is readable: the accepted connection (non-blocking, TCP_NODELAY
  // for request/response latency, SO_KEEPALIVE to find peers that vanished without a FIN) and its
  // `peer`, or -1 if there was none or `policy` refused it (closed at once, logged) with `open`
  // connections open, openFrom(peer) of them from that address.
  int acceptClient(const PeerPolicy& policy, size_t open, const std::function<size_t(uint32_t)>& openFrom, uint32_t& peer);
  // The peer's TCP port of an accepted connection (0 if the socket has none): audit records name it.
  static uint16_t peerPort(int fd);
  // Wakes the loop with kWakeStop and joins the I/O thread. Idempotent.
  void stop();

  int listenFd() const { return listenFd_; }
  int wakeFd() const { return wakeFds_[0]; }
  // The bound endpoint (the real port when 0 was asked for).
  Endpoint bound() const { return bound_; }

 private:
  Endpoint bound_;
  int listenFd_ = -1;
  int wakeFds_[2] = {-1, -1};
  std::thread thread_;
};

}  // namespace virtcom::proto::net
