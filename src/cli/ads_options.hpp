#pragma once
// The ADS server options that `exec` and `serve` share (docs/ads.md): one definition of the
// flags, their checks and the announcement, so both commands serve the soft PLC alike.
#include <expected>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bytecode/module.hpp"
#include "cli/peer_options.hpp"
#include "proto/ads/plc/plc_binding.hpp"

namespace virtcom::cli {

struct AdsServeOptions {
  std::string listen;  // --ads HOST:PORT; empty: no server
  std::string netId;   // --ads-netid; empty: 127.0.0.1.1.1
  std::string allow;   // --ads-allow: IPv4 peers or networks and/or client AmsNetIds; empty: any (loopback only)
  bool readOnly = false;
  std::string routePassword;  // --ads-route-password: what a UDP add route must carry; empty: refused
  std::string discovery = "48899";  // --ads-discovery: UDP port of identify / add route, or "off"
  std::string routesFile;  // --ads-routes: the route table's file (cell/ads_routes.hpp); empty: none
  bool enabled() const { return !listen.empty(); }
};

// Adds --ads, --ads-netid, --ads-allow, --ads-readonly, --ads-route-password, --ads-discovery and
// --ads-routes to `cmd`.
void addAdsServeOptions(CLI::App* cmd, AdsServeOptions& o);

// Checks the options (with the command's peer flags) and starts the server over `module` (which
// must outlive it). The error text names the option at fault ("--ads-netid: '1.2.3' is not an
// AmsNetId ...").
std::expected<std::unique_ptr<proto::ads::PlcServer>, std::string> startAdsServer(const AdsServeOptions& o, const PeerFlags& peers,
                                                                                  const bc::Module& module);

// "ads: serving on 127.0.0.1:48898 as AmsNetId 127.0.0.1.1.1, AMS ports 851 and 10000" on
// stderr: once the first image is published (e2e tests and scripts wait for it); before it, the
// discovery line ("ads: discovery on UDP 127.0.0.1:48899", or a warning why not).
void announceAdsServer(const AdsServeOptions& o, proto::ads::PlcServer& server);

}  // namespace virtcom::cli
