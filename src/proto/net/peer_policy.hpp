#pragma once
// Who may use a server, the one policy of every protocol server (ADS, Modbus, HTTP, OPC UA;
// docs/security.md): built once from the command line by makePeerPolicy(), checked at accept
// (admit) and per request (RequestBudget). A refused connection is logged with its peer and why.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/endpoint.hpp"
#include "core/text_result.hpp"

namespace virtcom::proto::net {

using virtcom::Ipv4Net;

// The defaults let 100 client processes of one test machine in at once.
struct PeerLimits {
  size_t maxConnections = 256;     // open connections of one server
  size_t maxPerPeer = 128;         // open connections from one IPv4 address
  uint32_t requestsPerSecond = 0;  // per connection (a burst of one second's worth); 0: no limit
};

enum class Refusal : uint8_t { None, NotAllowed, ServerFull, PeerFull, BadCredentials };
// "not in --ads-allow", "the server has its 256 connections", ...
std::string refusalText(Refusal why, std::string_view allowFlag, const PeerLimits& limits);

class PeerPolicy {
 public:
  // Any peer, the default limits: what a loopback server gets without options (and the tests).
  PeerPolicy() = default;
  PeerPolicy(std::vector<Ipv4Net> allowed, PeerLimits limits, std::string protocol, std::string allowFlag)
      : allowed_(std::move(allowed)), limits_(limits), protocol_(std::move(protocol)), allowFlag_(std::move(allowFlag)) {}

  // Whether `ipv4` may connect at all (the allow-list; empty: any).
  bool allows(uint32_t ipv4) const;
  // Whether a new connection from `ipv4` may stay, with `open` connections open of which
  // `openFromPeer` from that address. Logs a refusal. No allocation unless it refuses.
  Refusal admit(uint32_t ipv4, size_t open, size_t openFromPeer) const;
  // Writes "<protocol>: refused <peer>: <why>" to the log.
  void logRefusal(uint32_t ipv4, Refusal why) const;
  // Writes `line` to the log: stderr unless setLog was called.
  void log(const std::string& line) const;
  void setLog(std::function<void(const std::string&)> log) { log_ = std::move(log); }

  const PeerLimits& limits() const { return limits_; }
  std::vector<Ipv4Net>& allowed() { return allowed_; }
  const std::vector<Ipv4Net>& allowed() const { return allowed_; }

 private:
  std::vector<Ipv4Net> allowed_;
  PeerLimits limits_;
  std::string protocol_ = "server";
  std::string allowFlag_ = "the allow-list";
  std::function<void(const std::string&)> log_;
};

// What a server's options say about its peers (one shape for every protocol).
struct PeerOptions {
  std::string_view protocol;   // "ads", "modbus", "http": the log lines' prefix
  std::string_view listenFlag;  // "--ads": named in the error
  std::string_view allowFlag;   // "--ads-allow"
  std::string_view allowText;   // that option's text: ADDRESS or ADDRESS/BITS, comma-separated; "" if not given
  bool anyPeer = false;         // --allow-any-peer
  bool otherAllowList = false;  // the protocol names its peers another way too (ADS: AmsNetIds)
  PeerLimits limits;
};
// The policy of a server listening on `at`. Error text naming the option at fault; in
// particular when `at` is reachable beyond loopback and no allow-list nor --allow-any-peer says
// who may connect.
TextResult<PeerPolicy> makePeerPolicy(const Endpoint& at, const PeerOptions& o);

bool isLoopback(uint32_t ipv4);

// A connection's request-rate limit: a token bucket of `perSecond` tokens refilled with the
// monotonic time. take() is false when the client asked too fast; the server then answers
// "busy" in its protocol's words. No allocation.
class RequestBudget {
 public:
  explicit RequestBudget(uint32_t perSecond = 0) : perSecond_(perSecond), tokensNs_(int64_t{1'000'000'000}) {}
  bool take(int64_t nowNs);

 private:
  uint32_t perSecond_;
  int64_t tokensNs_;  // tokens × 1e9 / perSecond: time-denominated, so refilling is a subtraction
  int64_t lastNs_ = 0;
};

}  // namespace virtcom::proto::net
