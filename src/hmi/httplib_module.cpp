// The module virtcom-httplib.so: cpp-httplib (Debian libcpp-httplib-dev) serving an HttpHandler,
// loaded by HttpServer::start only when a command serves HTTP (hmi/http_module.hpp says why).
// It links cpp-httplib and nothing of virtcom but that header-only interface.
#include <httplib.h>

#include <chrono>
#include <memory>
#include <thread>
#include <type_traits>

#include "hmi/http_module.hpp"

namespace virtcom::hmi {

namespace {

Request toRequest(const httplib::Request& in) {
  Request r;
  r.method = in.method;
  r.path = in.path;
  for (const auto& [key, value] : in.params) r.query.emplace_back(key, value);
  r.body = in.body;
  r.authorization = in.get_header_value("Authorization");
  r.peer = in.remote_addr;
  r.peerPort = static_cast<uint16_t>(in.remote_port);
  return r;
}

void send(const Response& from, httplib::Response& to) {
  to.status = from.status;
  to.set_header("Cache-Control", "no-store");
  to.set_content(from.body, from.contentType);
}

class HttplibListener final : public HttpListener {
 public:
  HttplibListener(HttpHandler& handler, const HttpListenerOptions& options) : handler_(handler) {
    const size_t threads = options.poolThreads;
    server_.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
    server_.set_write_timeout(std::chrono::seconds(options.writeTimeoutS));
    route();
  }
  ~HttplibListener() override { stop(); }

  bool bind(const HttpListenerOptions& o) {
    port_ = o.port == 0 ? server_.bind_to_any_port(o.host) : (server_.bind_to_port(o.host, o.port) ? o.port : -1);
    if (port_ <= 0) return false;
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    return true;
  }
  uint16_t port() const override { return static_cast<uint16_t>(port_); }
  void stop() override {
    server_.stop();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void route() {
    server_.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (handler_.allows(req.remote_addr)) return httplib::Server::HandlerResponse::Unhandled;
      send(handler_.refusal(), res);
      return httplib::Server::HandlerResponse::Handled;
    });
    auto handler = [this](const httplib::Request& req, httplib::Response& res) {
      HttpAnswer answer = handler_.answer(toRequest(req));
      if (!answer.stream) return send(answer.response, res);
      res.status = answer.response.status;
      res.set_header("Cache-Control", "no-store");
      res.set_chunked_content_provider(
          answer.response.contentType,
          [stream = std::move(answer.stream)](size_t, httplib::DataSink& sink) {
            return stream([&sink](std::string_view chunk) { return sink.write(chunk.data(), chunk.size()); });
          },
          [ended = std::move(answer.ended)](bool) {
            if (ended) ended();
          });
    };
    server_.Get(".*", handler);
    server_.Post(".*", handler);
    server_.Put(".*", handler);
    server_.Delete(".*", handler);
  }

  HttpHandler& handler_;
  httplib::Server server_;
  std::thread thread_;
  int port_ = -1;
};

}  // namespace

}  // namespace virtcom::hmi

extern "C" [[gnu::visibility("default")]] virtcom::hmi::HttpListener* virtcomStartHttpListener(
    virtcom::hmi::HttpHandler& handler, const virtcom::hmi::HttpListenerOptions& options) {
  static_assert(std::is_same_v<decltype(&virtcomStartHttpListener), virtcom::hmi::StartHttpListener>);
  auto listener = std::make_unique<virtcom::hmi::HttplibListener>(handler, options);
  return listener->bind(options) ? listener.release() : nullptr;
}
