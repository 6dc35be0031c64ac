#include "proto/net/peer_policy.hpp"

#include <algorithm>
#include <iostream>

namespace virtcom::proto::net {

namespace {

constexpr uint32_t kLoopbackNet = 0x7f000000;  // 127.0.0.0/8
constexpr int64_t kSecondNs = 1'000'000'000;

}  // namespace

bool isLoopback(uint32_t ipv4) { return (ipv4 & 0xff000000u) == kLoopbackNet; }

std::string refusalText(Refusal why, std::string_view allowFlag, const PeerLimits& limits) {
  switch (why) {
    case Refusal::None: return "admitted";
    case Refusal::NotAllowed: return "not in " + std::string(allowFlag);
    case Refusal::ServerFull: return "the server has its " + std::to_string(limits.maxConnections) + " connections (--max-clients)";
    case Refusal::PeerFull:
      return "this address has its " + std::to_string(limits.maxPerPeer) + " connections (--max-clients-per-peer)";
    case Refusal::BadCredentials: return "wrong or no credentials";
  }
  return "refused";
}

bool PeerPolicy::allows(uint32_t ipv4) const {
  return allowed_.empty() || std::ranges::any_of(allowed_, [ipv4](const Ipv4Net& n) { return n.contains(ipv4); });
}

Refusal PeerPolicy::admit(uint32_t ipv4, size_t open, size_t openFromPeer) const {
  Refusal why = !allows(ipv4)                       ? Refusal::NotAllowed
                : open >= limits_.maxConnections    ? Refusal::ServerFull
                : openFromPeer >= limits_.maxPerPeer ? Refusal::PeerFull
                                                    : Refusal::None;
  if (why != Refusal::None) logRefusal(ipv4, why);
  return why;
}

void PeerPolicy::logRefusal(uint32_t ipv4, Refusal why) const {
  log(protocol_ + ": refused " + formatIpv4(ipv4) + ": " + refusalText(why, allowFlag_, limits_));
}

void PeerPolicy::log(const std::string& line) const {
  if (log_)
    log_(line);
  else
    std::cerr << line << "\n";
}

TextResult<PeerPolicy> makePeerPolicy(const Endpoint& at, const PeerOptions& o) {
  using Result = TextResult<PeerPolicy>;
  std::vector<Ipv4Net> allowed;
  if (!o.allowText.empty()) {
    auto list = parseAllowList(o.allowText);
    if (!list) return Result::failure(std::string(o.allowFlag) + ": " + list.error());
    allowed = *list;
  }
  if (!isLoopback(at.ipv4) && allowed.empty() && !o.otherAllowList && !o.anyPeer)
    return Result::failure(std::string(o.listenFlag) + ": " + formatIpv4(at.ipv4) +
                           " is reachable beyond this machine: name the peers allowed with " + std::string(o.allowFlag) +
                           " ADDRESS[/BITS],... (or let every peer in with --allow-any-peer), or bind 127.0.0.1");
  if (o.limits.maxConnections == 0 || o.limits.maxPerPeer == 0)
    return Result::failure("--max-clients and --max-clients-per-peer must be at least 1");
  return PeerPolicy(std::move(allowed), o.limits, std::string(o.protocol), std::string(o.allowFlag));
}

bool RequestBudget::take(int64_t nowNs) {
  if (perSecond_ == 0) return true;
  tokensNs_ = std::min(kSecondNs, tokensNs_ + std::max<int64_t>(0, nowNs - lastNs_));
  lastNs_ = nowNs;
  const int64_t costNs = kSecondNs / perSecond_;
  if (tokensNs_ < costNs) return false;
  tokensNs_ -= costNs;
  return true;
}

}  // namespace virtcom::proto::net
