#include "hmi/http_server.hpp"

#include <chrono>
#include <thread>

#include "core/bundled_module.hpp"

namespace virtcom::hmi {

namespace {

constexpr size_t kPoolThreads = HttpServer::kMaxStreams + 8;
constexpr int kWriteTimeoutS = 5;  // a stalled viewer ends its own stream

}  // namespace

HttpServer::HttpServer(Api& api, proto::net::PeerPolicy peers) : api_(api), peers_(std::move(peers)) {}

HttpServer::~HttpServer() {
  stop();
  listener_.reset();  // before the members its threads used
}

std::expected<std::unique_ptr<HttpServer>, std::string> HttpServer::start(Api& api, const Endpoint& at,
                                                                          proto::net::PeerPolicy peers) {
  auto startListener = bundledModuleSymbol(kHttpModule, kStartHttpListenerSymbol);
  if (!startListener) return std::unexpected(startListener.error());
  std::unique_ptr<HttpServer> s(new HttpServer(api, std::move(peers)));
  const HttpListenerOptions options{formatIpv4(at.ipv4), at.port, kPoolThreads, kWriteTimeoutS};
  s->listener_.reset(reinterpret_cast<StartHttpListener>(*startListener)(*s, options));
  if (!s->listener_) return std::unexpected("cannot listen on " + formatEndpoint(at) + " (address in use or not local?)");
  s->bound_ = {at.ipv4, s->listener_->port()};
  return s;
}

void HttpServer::stop() {
  if (stopping_.exchange(true)) return;
  if (listener_) listener_->stop();
}

bool HttpServer::allows(const std::string& peer) {
  if (peers_.allowed().empty()) return true;
  auto ipv4 = parseIpv4(peer);
  if (ipv4 && peers_.allows(*ipv4)) return true;
  if (ipv4) peers_.logRefusal(*ipv4, proto::net::Refusal::NotAllowed);
  return false;
}

Response HttpServer::refusal() { return errorResponse(403, "this address is not in --http-allow"); }

HttpAnswer HttpServer::answer(const Request& request) {
  ParsedRequest parsed = parseRequest(request, api_.access());
  if (parsed.route != Route::Stream) {
    ExternalWriter client{WriteProtocol::Http};
    if (auto ipv4 = parseIpv4(request.peer)) client.ipv4 = *ipv4;
    client.port = request.peerPort;
    return {api_.handle(parsed, client), {}, {}};
  }
  if (streams_.fetch_add(1) >= kMaxStreams) {
    streams_.fetch_sub(1);
    return {errorResponse(503, "too many viewers at once"), {}, {}};
  }
  std::shared_ptr<StreamSession> session = api_.openStream(parsed);
  HttpAnswer a;
  a.response.contentType = "text/event-stream";
  a.stream = [this, session, quiet = 0](const std::function<bool(std::string_view)>& write) mutable {
    std::string frame = session->nextFrame();
    if (frame.empty() && (quiet += kFramePeriodMs) >= kHeartbeatMs) frame = ":";  // an SSE comment line
    if (!frame.empty()) {
      quiet = 0;
      std::string event = frame == ":" ? ":\n\n" : "data: " + frame + "\n\n";
      if (!write(event)) return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(kFramePeriodMs));
    return !stopping_.load();
  };
  a.ended = [this] { streams_.fetch_sub(1); };
  return a;
}

}  // namespace virtcom::hmi
