#include "cell/opcua_settings.hpp"

#include "cell/peer_settings.hpp"

namespace virtcom::cell {

namespace {

// `endpoint: opc.tcp://HOST:PORT[/PATH]` into s.url and s.server.
void readEndpoint(ConfigReader& r, const ConfigNode& node, OpcuaClientSettings& s) {
  s.url = r.requireString("endpoint");
  if (s.url.empty()) return;
  const ConfigNode* at = node.find("endpoint");
  s.endpointLoc = at->loc();
  auto server = opcuaServerOf(s.url);
  if (server) s.server = *server;
  else r.error(at->loc(), "'endpoint': " + server.error());
}

// `security:`, `pki:` and `trust_server:` into s.
void readSecurity(ConfigReader& r, const ConfigNode& node, const std::filesystem::path& cellDir, OpcuaClientSettings& s) {
  const std::string security = r.optString("security", "none");
  if (security == "sign") s.security = OpcuaSecurity::Sign;
  else if (security == "sign-encrypt") s.security = OpcuaSecurity::SignAndEncrypt;
  else if (security != "none")
    r.error(node.find("security")->loc(), "'security' must be none, sign or sign-encrypt (Basic256Sha256), not '" + security + "'");
  const std::string pki = r.optString("pki", "");
  if (!pki.empty()) s.pkiDir = (cellDir / pki).lexically_normal().string();
  const std::string trust = r.optString("trust_server", "");
  if (!trust.empty() && trust != "any")
    r.error(node.find("trust_server")->loc(), "'trust_server' can only be 'any' (every server certificate, for labs), not '" + trust +
                                                   "'; leave it out to trust the certificates in the PKI folder's trusted/certs");
  s.trustAnyServer = trust == "any";
  for (const char* key : {"pki", "trust_server"})
    if (s.security == OpcuaSecurity::None && node.find(key))
      r.error(node.find(key)->loc(), std::string("'") + key + "' is for a secured link: it needs 'security: sign' or 'security: sign-encrypt'");
}

}  // namespace

std::expected<Endpoint, std::string> opcuaServerOf(std::string_view url) {
  constexpr std::string_view kScheme = "opc.tcp://";
  const std::string expected = " (expected opc.tcp://HOST:PORT, e.g. opc.tcp://127.0.0.1:4840)";
  if (!url.starts_with(kScheme)) return std::unexpected("'" + std::string(url) + "' is not an opc.tcp URL" + expected);
  std::string_view hostPort = url.substr(kScheme.size());
  hostPort = hostPort.substr(0, hostPort.find('/'));
  auto parsed = parseEndpoint(std::string(hostPort));
  if (parsed && parsed->port != 0) return *parsed;
  return std::unexpected((parsed ? std::string("port 0 cannot be connected to") : parsed.error()) + expected);
}

void readOpcuaClient(OpcuaClientSettings& s, const ConfigNode& node, const std::filesystem::path& cellDir, Diagnostics& diags) {
  ConfigReader r(node, diags, "'plc: opcua'");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "'plc: opcua' must be a map with 'endpoint: opc.tcp://HOST:PORT' of the external PLC's OPC UA server");
    return;
  }
  s.endpointLoc = node.loc();
  readEndpoint(r, node, s);
  readSecurity(r, node, cellDir, s);
  s.user = r.optString("user", "");
  s.password = r.optString("password", "");
  if (s.user.empty() != s.password.empty())
    r.error((s.user.empty() ? node.find("password") : node.find("user"))->loc(),
            "'user' and 'password' go together (a UserName identity); leave both out for an anonymous session");
  s.nodePrefix = r.optString("node_prefix", s.nodePrefix);
  if (const ConfigNode* nodes = r.child("nodes")) {
    if (nodes->kind() != ConfigNode::Kind::Map) {
      r.error(nodes->loc(), "'nodes' must be a map PLC variable: node id or browse path (MAIN.start: \"ns=2;i=17\" or \"/4:MAIN/4:start\")");
    } else {
      for (const auto& [variable, id] : nodes->entries()) {
        if (id.kind() != ConfigNode::Kind::Scalar || id.scalar().empty())
          r.error(id.loc(), "'nodes': '" + variable + "' must name a node id or a browse path");
        else s.nodes.push_back({variable, id.scalar(), id.loc()});
      }
    }
  }
  s.pollNs = readLinkDurationNs(r, node, "poll", 0.01);
  s.subscribe = r.optBool("subscribe", true);
  s.timeoutNs = readLinkDurationNs(r, node, "timeout", 0.5);
  s.faultOnLoss = readFaultOnLoss(r, node);
  s.disconnectWhenStopped = r.optBool("disconnect_when_simulation_stops", true);
  r.rejectUnknownKeys();
}

}  // namespace virtcom::cell
