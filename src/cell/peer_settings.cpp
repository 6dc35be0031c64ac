#include "cell/peer_settings.hpp"

#include <cmath>

namespace virtcom::cell {

void readPeerAddress(ConfigReader& r, const ConfigNode& node, const char* example, std::string& text, Endpoint& endpoint) {
  text = r.requireString("address");
  if (text.empty()) return;
  auto parsed = parseEndpoint(text);
  if (parsed && parsed->port != 0) {
    endpoint = *parsed;
    return;
  }
  r.error(node.find("address")->loc(), "'address': " + (parsed ? std::string("port 0 cannot be connected to") : parsed.error()) +
                                           " (expected HOST:PORT, e.g. " + example + ")");
}

int64_t readLinkDurationNs(ConfigReader& r, const ConfigNode& node, const char* key, double defaultS) {
  const auto ns = static_cast<int64_t>(std::llround(r.optQuantity(key, Dimension::Time, defaultS) * 1e9));
  if (ns < 1'000'000) r.error(node.find(key)->loc(), std::string("'") + key + "' must be at least 1 ms");
  return ns;
}

bool readFaultOnLoss(ConfigReader& r, const ConfigNode& node) {
  const std::string onLoss = r.optString("on_loss", "fault");
  if (onLoss != "fault" && onLoss != "hold") r.error(node.find("on_loss")->loc(), "'on_loss' must be fault or hold, not '" + onLoss + "'");
  return onLoss == "fault";
}

}  // namespace virtcom::cell
