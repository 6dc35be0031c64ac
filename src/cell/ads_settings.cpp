#include "cell/ads_settings.hpp"

#include "cell/peer_settings.hpp"

namespace virtcom::cell {

namespace {

// `key: a.b.c.d.e.f` (absent: none); a malformed AmsNetId is reported at the key.
std::optional<AmsNetId> readNetId(ConfigReader& r, const ConfigNode& node, const char* key) {
  const std::string text = r.optString(key, "");
  if (text.empty()) return std::nullopt;
  auto id = parseNetId(text);
  if (!id) {
    r.error(node.find(key)->loc(), std::string("'") + key + "': " + id.error());
    return std::nullopt;
  }
  return *id;
}

}  // namespace

void readAdsClient(AdsClientSettings& s, const ConfigNode& node, Diagnostics& diags) {
  ConfigReader r(node, diags, "'plc: ads'");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "'plc: ads' must be a map with 'address: HOST:PORT' of the external PLC's AMS router");
    return;
  }
  readPeerAddress(r, node, "127.0.0.1:48898", s.address, s.router);
  s.addressLoc = node.find("address") ? node.find("address")->loc() : node.loc();
  s.netId = readNetId(r, node, "netid").value_or(s.netId);
  int64_t port = r.optInt("port", 851);
  if (port < 1 || port > 65535) r.error(node.find("port")->loc(), "'port' must be an AMS port 1..65535 (851 = PLC runtime 1)");
  s.port = static_cast<uint16_t>(port);
  s.localNetId = readNetId(r, node, "local_netid");
  s.timeoutNs = readLinkDurationNs(r, node, "timeout", 0.5);
  s.faultOnLoss = readFaultOnLoss(r, node);
  s.disconnectWhenStopped = r.optBool("disconnect_when_simulation_stops", true);
  r.rejectUnknownKeys();
}

}  // namespace virtcom::cell
