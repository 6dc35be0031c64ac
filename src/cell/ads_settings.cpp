#include "cell/ads_settings.hpp"

#include <cmath>

#include "proto/ads/ams.hpp"
#include "proto/net/endpoint.hpp"

namespace virtcom::cell {

void readAdsClient(AdsClientSettings& s, const ConfigNode& node, Diagnostics& diags) {
  ConfigReader r(node, diags, "'plc: ads'");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "'plc: ads' must be a map with 'address: HOST:PORT' of the external PLC's AMS router");
    return;
  }
  s.address = r.requireString("address");
  s.addressLoc = node.find("address") ? node.find("address")->loc() : node.loc();
  if (!s.address.empty()) {
    auto endpoint = proto::net::parseEndpoint(s.address);
    if (!endpoint || endpoint->port == 0)
      r.error(node.find("address")->loc(), "'address': " + (endpoint ? std::string("port 0 cannot be connected to") : endpoint.error()) +
                                               " (expected HOST:PORT, e.g. 127.0.0.1:48898)");
  }
  auto netId = [&](const char* key, std::string& out) {
    out = r.optString(key, out);
    if (!out.empty() && !proto::ads::parseNetId(out))
      r.error(node.find(key)->loc(), std::string("'") + key + "': '" + out + "' is not an AmsNetId (six numbers 0-255, e.g. 192.168.1.10.1.1)");
  };
  netId("netid", s.netId);
  int64_t port = r.optInt("port", 851);
  if (port < 1 || port > 65535) r.error(node.find("port")->loc(), "'port' must be an AMS port 1..65535 (851 = PLC runtime 1)");
  s.port = static_cast<uint16_t>(port);
  netId("local_netid", s.localNetId);
  s.timeoutNs = static_cast<int64_t>(std::llround(r.optQuantity("timeout", Dimension::Time, 0.5) * 1e9));
  if (s.timeoutNs < 1'000'000) r.error(node.find("timeout")->loc(), "'timeout' must be at least 1 ms");
  std::string onLoss = r.optString("on_loss", "fault");
  if (onLoss != "fault" && onLoss != "hold") r.error(node.find("on_loss")->loc(), "'on_loss' must be fault or hold, not '" + onLoss + "'");
  s.faultOnLoss = onLoss == "fault";
  s.disconnectWhenStopped = r.optBool("disconnect_when_simulation_stops", true);
  r.rejectUnknownKeys();
}

}  // namespace virtcom::cell
