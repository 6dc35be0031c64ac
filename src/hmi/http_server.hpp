#pragma once
// The HMI's HTTP server: cpp-httplib (Debian libcpp-httplib-dev) serving the Api on a pool of
// threads, none of them the simulation's. This file is the thin glue: every request is read by
// parseRequest() and answered by Api; the stream is sent as server-sent events, one frame per
// kFramePeriod at most, each viewer on its own pool thread, so a slow or dead browser only
// delays its own frames. cpp-httplib itself is called only by the module virtcom-httplib.so
// (http_module.hpp), loaded by start().
#include <atomic>
#include <cstdint>
#include <expected>
#include <memory>
#include <string>

#include "core/endpoint.hpp"
#include "hmi/api.hpp"
#include "hmi/http_module.hpp"
#include "proto/net/peer_policy.hpp"

namespace virtcom::hmi {

class HttpServer final : private HttpHandler {
 public:
  static constexpr int kFramePeriodMs = 50;   // 20 frames a second per viewer at most
  static constexpr int kMaxStreams = 24;      // viewers at once; the pool has room for requests besides
  static constexpr int kHeartbeatMs = 2000;   // an SSE comment when nothing changed: finds dead peers

  // Binds `at` (port 0: a free port) and serves `api` (which must outlive the server) to the peers
  // `peers` allows (docs/security.md; others get 403, logged). Error text if it cannot bind or
  // the module cannot be loaded.
  static std::expected<std::unique_ptr<HttpServer>, std::string> start(Api& api, const Endpoint& at,
                                                                      proto::net::PeerPolicy peers);
  ~HttpServer() override;  // stop()
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  Endpoint bound() const { return bound_; }
  // Ends the streams, stops listening and joins the threads. Idempotent.
  void stop();

 private:
  HttpServer(Api& api, proto::net::PeerPolicy peers);
  bool allows(const std::string& peer) override;
  Response refusal() override;
  HttpAnswer answer(const Request& request) override;

  Api& api_;
  proto::net::PeerPolicy peers_;
  std::unique_ptr<HttpListener> listener_;  // its threads call back into this object
  Endpoint bound_;
  std::atomic<bool> stopping_{false};
  std::atomic<int> streams_{0};
};

}  // namespace virtcom::hmi
