#pragma once
// The peer policy flags every server of a command shares (docs/security.md): --allow-any-peer
// and the connection and request-rate limits, registered once per command and applied to each
// of its servers with that server's --*-allow list.
#include <expected>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "proto/net/peer_policy.hpp"

namespace virtcom::cli {

struct PeerFlags {
  bool anyPeer = false;  // --allow-any-peer
  proto::net::PeerLimits limits;
};

// Adds --allow-any-peer and, with `withLimits` (commands with a Modbus or ADS server), --max-clients,
// --max-clients-per-peer and --max-request-rate.
void addPeerFlags(CLI::App* cmd, PeerFlags& f, bool withLimits);

// The policy of the server `listenFlag` (e.g. "--ads", serving `protocol` "ads") on `at`, with
// the allow-list text of its `allowFlag`. Error text naming the option at fault; in particular
// when `at` is beyond loopback and neither an allow-list nor --allow-any-peer is given.
// `otherAllowList`: the server names its peers another way as well (ADS: AmsNetIds).
std::expected<proto::net::PeerPolicy, std::string> peerPolicy(const Endpoint& at, const PeerFlags& f, std::string_view protocol,
                                                              std::string_view listenFlag, std::string_view allowFlag,
                                                              std::string_view allowText, bool otherAllowList = false);

}  // namespace virtcom::cli
