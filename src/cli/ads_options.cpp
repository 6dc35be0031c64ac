#include "cli/ads_options.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cell/ads_routes.hpp"
#include "proto/ads/ams.hpp"
#include "proto/net/endpoint.hpp"

namespace virtcom::cli {

namespace {

// Splits "--ads-allow A,B,..." into client AmsNetIds (6 numbers), kept in `config`, and the
// IPv4 peers and networks (ADDRESS[/BITS]), returned as the peer policy's allow-list text.
std::string splitAdsAllow(std::string_view text, proto::ads::ServerConfig& config) {
  std::string peers;
  while (!text.empty()) {
    auto comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    if (auto id = proto::ads::parseNetId(item))
      config.allowedNetIds.push_back(*id);
    else if (!item.empty())
      peers.append(peers.empty() ? "" : ",").append(item);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return peers;
}

// The routes of `--ads-routes FILE` into the lists in use: `config`'s NetIds and `peerList`'s
// addresses; a route a UDP add route adds is appended to the file. Error text on failure.
std::string useRoutesFile(const std::string& path, proto::ads::ServerConfig& config, std::string& peerList) {
  std::string text;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream content;
    content << in.rdbuf();
    if (!in || std::filesystem::is_directory(path, ec)) return "cannot read '" + path + "'";
    text = content.str();
  }
  SourceManager sources;
  Diagnostics diags;
  auto routes = cell::parseAdsRoutes(path, text, sources, diags);
  if (!routes) {
    std::string rendered = diags.render(sources);
    while (!rendered.empty() && rendered.back() == '\n') rendered.pop_back();
    return rendered;
  }
  for (const cell::AdsRoute& r : *routes) {
    config.allowedNetIds.push_back(r.netId);
    peerList.append(peerList.empty() ? "" : ",").append(proto::net::formatIpv4(r.ipv4));
  }
  config.onRouteAdded = [path](const AmsNetId& netId, uint32_t ipv4) {
    std::string problem = cell::appendAdsRoute(path, {"added-" + proto::net::formatIpv4(ipv4), netId, ipv4});
    if (!problem.empty()) std::cerr << "ads: --ads-routes: " << problem << "\n";
  };
  return "";
}

}  // namespace

void addAdsServeOptions(CLI::App* cmd, AdsServeOptions& o) {
  cmd->add_option("--ads", o.listen, "serve the PLC over ADS (AMS/TCP, TwinCAT 3 runtime on AMS port 851) on HOST:PORT, e.g. 127.0.0.1:48898 (see docs/ads.md); implies --speed 1");
  cmd->add_option("--ads-netid", o.netId, "AmsNetId of the --ads server (default 127.0.0.1.1.1; 127.0.0.1.1.1 is always accepted too)");
  cmd->add_option("--ads-allow", o.allow,
                  "comma-separated IPv4 peers (ADDRESS or ADDRESS/BITS) and/or client AmsNetIds allowed to use --ads (needed to bind "
                  "beyond loopback; see docs/security.md)");
  cmd->add_flag("--ads-readonly", o.readOnly, "refuse every ADS write and RUN/STOP request (error 0x704)");
  cmd->add_option("--ads-route-password", o.routePassword,
                  "the password a UDP add route (pyads add_route_to_plc, TwinCAT's Add Route dialog) must carry; without it every "
                  "add route is refused (0x704). An accepted route lets its AmsNetId and address in (see docs/ads.md, Routes)");
  cmd->add_option("--ads-routes", o.routesFile,
                  "the ADS route table in a file (YAML: routes: - {name, netid, address}; see docs/ads.md, Routes): its AmsNetIds "
                  "and addresses are let in, with those of --ads-allow; a route added over UDP with --ads-route-password is "
                  "appended to it, as TwinCAT keeps StaticRoutes.xml. Created when absent");
  cmd->add_option("--ads-discovery", o.discovery,
                  "UDP port of the ADS discovery service (identify, add route: adstool HOST netid, pyads add_route_to_plc) on the --ads address; 0 picks a free port, 'off' disables it (default 48899)");
}

std::expected<std::unique_ptr<proto::ads::PlcServer>, std::string> startAdsServer(const AdsServeOptions& o, const PeerFlags& peers,
                                                                                  const bc::Module& module) {
  namespace ads = proto::ads;
  auto endpoint = proto::net::parseEndpoint(o.listen);
  if (!endpoint) return std::unexpected("--ads: " + endpoint.error());
  ads::ServerConfig config;
  config.listen = *endpoint;
  config.device.readOnly = o.readOnly;
  config.routePassword = o.routePassword;
  if (!o.netId.empty()) {
    auto id = ads::parseNetId(o.netId);
    if (!id) return std::unexpected("--ads-netid: " + id.error());
    config.device.netId = *id;
  }
  std::string peerList = splitAdsAllow(o.allow, config);
  if (!o.allow.empty() && peerList.empty() && config.allowedNetIds.empty())
    return std::unexpected(std::string("--ads-allow: the allow-list names no address"));
  if (!o.routesFile.empty()) {
    if (std::string problem = useRoutesFile(o.routesFile, config, peerList); !problem.empty())
      return std::unexpected("--ads-routes: " + problem);
  }
  auto policy = peerPolicy(*endpoint, peers, "ads", "--ads", "--ads-allow", peerList, !config.allowedNetIds.empty());
  if (!policy) return std::unexpected(policy.error());
  config.peers = std::move(*policy);
  if (o.discovery == "off") {
    config.discoveryPort.reset();
  } else {
    // The port on the --ads host, with the endpoint parser's checks and message.
    auto at = proto::net::parseEndpoint(proto::net::formatIpv4(endpoint->ipv4) + ":" + o.discovery);
    if (!at) return std::unexpected("--ads-discovery: " + at.error() + " (or 'off')");
    config.discoveryPort = at->port;
  }
  auto server = ads::PlcServer::start(config, module);
  if (!server) return std::unexpected("--ads: " + server.error());
  return server;
}

void announceAdsServer(const AdsServeOptions& o, proto::ads::PlcServer& server) {
  if (auto udp = server.server().discoveryEndpoint())
    std::cerr << "ads: discovery on UDP " << proto::net::formatEndpoint(*udp) << "\n";
  else if (!server.server().discoveryProblem().empty())
    std::cerr << "warning: ads: discovery not served (" << server.server().discoveryProblem() << ")\n";
  std::cerr << "ads: serving on " << proto::net::formatEndpoint(server.server().endpoint()) << " as AmsNetId "
            << (o.netId.empty() ? "127.0.0.1.1.1" : o.netId) << ", AMS ports 851 and 10000\n";
}

}  // namespace virtcom::cli
