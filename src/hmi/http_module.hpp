#pragma once
// The interface between the HMI's HTTP server (http_server.cpp, in the executable) and the module
// virtcom-httplib.so (httplib_module.cpp), the only code that calls cpp-httplib. cpp-httplib
// brings OpenSSL, brotli and zlib, whose loading and initialisation cost every command about
// 11 ms of CPU when the executable linked them; as a module they are loaded only by the commands
// that serve HTTP (core/bundled_module.hpp, docs/performance.md "Start-up").
// Header-only on purpose: the module needs no symbol of the executable, only these types and the
// standard library, and the executable none of the module's but the one function it looks up.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "hmi/request.hpp"

namespace virtcom::hmi {

// One answer: a whole response, or, when `stream` is set, a stream of chunks of
// `response.contentType` (`response.body` unused).
struct HttpAnswer {
  Response response;
  // Called again and again on the request's own pool thread with a writer of one chunk (which
  // returns false once the peer is gone); returns false to end the stream. `ended` (if set) runs
  // once when the stream ends, whatever ended it.
  std::function<bool(const std::function<bool(std::string_view)>& write)> stream;
  std::function<void()> ended;
};

// The executable's side, called on the module's pool threads, several at once.
class HttpHandler {
 public:
  virtual ~HttpHandler() = default;
  // Whether `peer` (the remote IPv4 address as text) may be served at all; else `refusal()` is
  // sent, whatever the method and path.
  virtual bool allows(const std::string& peer) = 0;
  virtual Response refusal() = 0;
  virtual HttpAnswer answer(const Request& request) = 0;
};

// The module's side: a bound server listening on its own thread.
class HttpListener {
 public:
  virtual ~HttpListener() = default;
  virtual uint16_t port() const = 0;  // the bound port (the real one when 0 was asked for)
  virtual void stop() = 0;            // stops listening, ends the streams, joins the threads. Idempotent.
};

struct HttpListenerOptions {
  std::string host;       // IPv4 text
  uint16_t port = 0;      // 0: any free port
  size_t poolThreads = 1;
  int writeTimeoutS = 5;  // a stalled peer ends its own request or stream
};

// The module's one function (extern "C", found by name): a listener bound as `options` say,
// answering through `handler` (which must outlive it); nullptr if it cannot bind.
using StartHttpListener = HttpListener* (*)(HttpHandler& handler, const HttpListenerOptions& options);
inline constexpr const char* kHttpModule = "virtcom-httplib.so";
inline constexpr const char* kStartHttpListenerSymbol = "virtcomStartHttpListener";

}  // namespace virtcom::hmi
