#include "cli/peer_options.hpp"

namespace virtcom::cli {

void addPeerFlags(CLI::App* cmd, PeerFlags& f, bool withLimits) {
  cmd->add_flag("--allow-any-peer", f.anyPeer,
                "let every peer use a server bound beyond loopback (instead of its --*-allow list; see docs/security.md)");
  if (!withLimits) return;
  cmd->add_option("--max-clients", f.limits.maxConnections, "connections each server (--ads, --modbus) keeps open at once; more are closed at once and logged")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-clients-per-peer", f.limits.maxPerPeer, "connections from one IPv4 address each server keeps open at once")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-request-rate", f.limits.requestsPerSecond,
                  "requests per second one connection may make (bursts of one second's worth); beyond it the request is answered "
                  "'busy' (Modbus exception 06, ADS error 0x708); 0: no limit")
      ->capture_default_str();
}

std::expected<proto::net::PeerPolicy, std::string> peerPolicy(const Endpoint& at, const PeerFlags& f, std::string_view protocol,
                                                              std::string_view listenFlag, std::string_view allowFlag,
                                                              std::string_view allowText, bool otherAllowList) {
  proto::net::PeerOptions o{protocol, listenFlag, allowFlag, allowText, f.anyPeer, otherAllowList, f.limits};
  auto policy = proto::net::makePeerPolicy(at, o);
  if (!policy) return std::unexpected(policy.error());
  return *policy;
}

}  // namespace virtcom::cli
