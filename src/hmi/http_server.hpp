#pragma once
// The HMI's HTTP server: cpp-httplib (Debian libcpp-httplib-dev) serving the Api on a pool of
// threads, none of them the simulation's. This file is the thin glue: every request is read by
// parseRequest() and answered by Api; the stream is sent as server-sent events, one frame per
// kFramePeriod at most, each viewer on its own pool thread, so a slow or dead browser only
// delays its own frames.
#include <atomic>
#include <cstdint>
#include <expected>
#include <memory>
#include <string>
#include <thread>

#include "core/endpoint.hpp"
#include "hmi/api.hpp"
#include "proto/net/peer_policy.hpp"

namespace httplib {
class Server;
}

namespace virtcom::hmi {

class HttpServer {
 public:
  static constexpr int kFramePeriodMs = 50;   // 20 frames a second per viewer at most
  static constexpr int kMaxStreams = 24;      // viewers at once; the pool has room for requests besides
  static constexpr int kHeartbeatMs = 2000;   // an SSE comment when nothing changed: finds dead peers

  // Binds `at` (port 0: a free port) and serves `api` (which must outlive the server) to the peers
  // `peers` allows (docs/security.md; others get 403, logged). Error text if it cannot bind.
  static std::expected<std::unique_ptr<HttpServer>, std::string> start(Api& api, const Endpoint& at,
                                                                      proto::net::PeerPolicy peers);
  ~HttpServer();  // stop()
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  Endpoint bound() const { return bound_; }
  // Ends the streams, stops listening and joins the threads. Idempotent.
  void stop();

 private:
  HttpServer(Api& api, proto::net::PeerPolicy peers);
  void route();

  Api& api_;
  proto::net::PeerPolicy peers_;
  std::unique_ptr<httplib::Server> server_;
  std::thread listener_;
  Endpoint bound_;
  std::atomic<bool> stopping_{false};
  std::atomic<int> streams_{0};
};

}  // namespace virtcom::hmi
