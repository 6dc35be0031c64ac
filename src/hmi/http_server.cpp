#include "hmi/http_server.hpp"

#include <algorithm>
#include <chrono>

#include <httplib.h>

namespace virtcom::hmi {

namespace {

constexpr size_t kPoolThreads = HttpServer::kMaxStreams + 8;

Request toRequest(const httplib::Request& in) {
  Request r;
  r.method = in.method;
  r.path = in.path;
  for (const auto& [key, value] : in.params) r.query.emplace_back(key, value);
  r.body = in.body;
  r.authorization = in.get_header_value("Authorization");
  return r;
}

void send(const Response& from, httplib::Response& to) {
  to.status = from.status;
  to.set_header("Cache-Control", "no-store");
  to.set_content(from.body, from.contentType);
}

}  // namespace

HttpServer::HttpServer(Api& api, proto::net::PeerPolicy peers)
    : api_(api), peers_(std::move(peers)), server_(std::make_unique<httplib::Server>()) {}

HttpServer::~HttpServer() { stop(); }

std::expected<std::unique_ptr<HttpServer>, std::string> HttpServer::start(Api& api, const Endpoint& at,
                                                                          proto::net::PeerPolicy peers) {
  std::unique_ptr<HttpServer> s(new HttpServer(api, std::move(peers)));
  s->server_->new_task_queue = [] { return new httplib::ThreadPool(kPoolThreads); };
  s->server_->set_write_timeout(std::chrono::seconds(5));  // a stalled viewer ends its own stream
  s->route();
  const std::string host = formatIpv4(at.ipv4);
  int port = at.port == 0 ? s->server_->bind_to_any_port(host) : (s->server_->bind_to_port(host, at.port) ? at.port : -1);
  if (port <= 0) return std::unexpected("cannot listen on " + formatEndpoint(at) + " (address in use or not local?)");
  s->bound_ = {at.ipv4, static_cast<uint16_t>(port)};
  s->listener_ = std::thread([server = s->server_.get()] { server->listen_after_bind(); });
  return s;
}

void HttpServer::stop() {
  if (stopping_.exchange(true)) return;
  server_->stop();
  if (listener_.joinable()) listener_.join();
}

void HttpServer::route() {
  server_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (peers_.allowed().empty()) return httplib::Server::HandlerResponse::Unhandled;
    auto peer = parseIpv4(req.remote_addr);
    if (peer && peers_.allows(*peer)) return httplib::Server::HandlerResponse::Unhandled;
    if (peer) peers_.logRefusal(*peer, proto::net::Refusal::NotAllowed);
    send(errorResponse(403, "this address is not in --http-allow"), res);
    return httplib::Server::HandlerResponse::Handled;
  });
  auto handler = [this](const httplib::Request& req, httplib::Response& res) {
    ParsedRequest parsed = parseRequest(toRequest(req), api_.access());
    if (parsed.route != Route::Stream) return send(api_.handle(parsed), res);
    if (streams_.fetch_add(1) >= kMaxStreams) {
      streams_.fetch_sub(1);
      return send(errorResponse(503, "too many viewers at once"), res);
    }
    std::shared_ptr<StreamSession> session = api_.openStream(parsed);
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, session, quiet = 0](size_t, httplib::DataSink& sink) mutable {
          std::string frame = session->nextFrame();
          if (frame.empty() && (quiet += kFramePeriodMs) >= kHeartbeatMs) frame = ":";  // an SSE comment line
          if (!frame.empty()) {
            quiet = 0;
            std::string event = frame == ":" ? ":\n\n" : "data: " + frame + "\n\n";
            if (!sink.write(event.data(), event.size())) return false;
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(kFramePeriodMs));
          return !stopping_.load();
        },
        [this](bool) { streams_.fetch_sub(1); });
  };
  server_->Get(".*", handler);
  server_->Post(".*", handler);
  server_->Put(".*", handler);
  server_->Delete(".*", handler);
}

}  // namespace virtcom::hmi
