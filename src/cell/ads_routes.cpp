#include "cell/ads_routes.hpp"

#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/atomic_file.hpp"
#include "core/config_node.hpp"
#include "core/endpoint.hpp"

namespace virtcom::cell {

namespace {

// YAML's null (an empty file, `routes:` with nothing after it) reads as an empty scalar.
bool isEmpty(const ConfigNode& n) { return n.kind() == ConfigNode::Kind::Null || (n.kind() == ConfigNode::Kind::Scalar && n.scalar().empty()); }

std::optional<AdsRoute> readRoute(const ConfigNode& node, Diagnostics& diags) {
  ConfigReader r(node, diags, "a route");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "a route must be a map with 'name', 'netid' (AmsNetId) and 'address' (IPv4)");
    return std::nullopt;
  }
  AdsRoute route;
  route.name = r.requireString("name");
  const std::string netId = r.requireString("netid");
  if (!netId.empty()) {
    if (auto id = parseNetId(netId)) route.netId = *id;
    else r.error(node.find("netid")->loc(), "'netid': " + id.error());
  }
  const std::string address = r.requireString("address");
  if (!address.empty()) {
    if (auto ip = parseIpv4(address)) route.ipv4 = *ip;
    else r.error(node.find("address")->loc(), "'address': " + ip.error() + " (the peer's IPv4 address, e.g. 192.168.1.20)");
  }
  r.rejectUnknownKeys();
  if (!r.ok()) return std::nullopt;
  return route;
}

}  // namespace

std::optional<std::vector<AdsRoute>> parseAdsRoutes(const std::string& path, const std::string& text, SourceManager& sources,
                                                    Diagnostics& diags) {
  std::vector<AdsRoute> routes;
  ConfigNode root;
  if (!parseYaml(path, text, sources, diags, root)) return std::nullopt;
  if (isEmpty(root)) return routes;
  ConfigReader r(root, diags, "the ADS routes file");
  if (root.kind() != ConfigNode::Kind::Map) {
    r.error(root.loc(), "an ADS routes file is a map with 'routes:', a list of routes (name, netid, address)");
    return std::nullopt;
  }
  const ConfigNode* list = r.child("routes");
  r.rejectUnknownKeys();
  bool ok = r.ok();
  if (list && list->kind() == ConfigNode::Kind::List) {
    for (const ConfigNode& item : list->items()) {
      auto route = readRoute(item, diags);
      if (route) routes.push_back(std::move(*route));
      else ok = false;
    }
  } else if (list && !isEmpty(*list)) {
    r.error(list->loc(), "'routes' must be a list of routes, each with 'name', 'netid' and 'address'");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return routes;
}

std::string appendAdsRoute(const std::string& path, const AdsRoute& route) {
  // The whole file is written anew and renamed into place (core/atomic_file.hpp): a kill -9 in
  // the middle leaves the file as it was before, never half a route that would stop the next start.
  std::string text;
  if (std::ifstream in(path); in) {
    std::ostringstream old;
    old << in.rdbuf();
    text = old.str();
  }
  if (text.empty()) text = "# ADS routes of the virtcom ADS server (docs/ads.md, Routes)\nroutes:\n";
  else if (text.back() != '\n') text += '\n';
  text += "  - name: " + route.name + "\n    netid: " + formatNetId(route.netId) + "\n    address: " + formatIpv4(route.ipv4) + "\n";
  if (std::string why = replaceFile(path, text); !why.empty()) return "cannot write the ADS routes file '" + path + "': " + why;
  return "";
}

}  // namespace virtcom::cell
