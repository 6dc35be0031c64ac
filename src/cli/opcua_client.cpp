#include "cli/opcua_client.hpp"

#include <iostream>

#include "cli/external_wires.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "proto/opcua/pki.hpp"

namespace virtcom::cli {

namespace {

const cell::OpcuaNodeName* namedNode(const cell::OpcuaClientSettings& s, const std::string& variable) {
  for (const cell::OpcuaNodeName& n : s.nodes)
    if (n.variable == variable) return &n;
  return nullptr;
}

}  // namespace

std::string opcuaNodeOf(const cell::OpcuaClientSettings& s, const std::string& variable) {
  if (const cell::OpcuaNodeName* named = namedNode(s, variable)) return named->node;
  if (variable.starts_with("ns=") || variable.starts_with("i=") || variable.starts_with("s=")) return variable;
  return s.nodePrefix + variable;
}

std::unique_ptr<proto::opcua::ClientBridge> startOpcuaBridge(cell::Cell& cell, const SourceManager& sources, const std::string& role) {
  namespace ua = proto::opcua;
  const cell::OpcuaClientSettings& s = *cell.plcOpcua;
  ua::BridgeConfig config;
  config.client.server = s.server;
  config.client.endpointUrl = s.url;
  config.client.security = static_cast<ua::SecurityMode>(s.security);  // the same values
  config.client.pkiDir = s.pkiDir.empty() ? ua::defaultClientPkiDir() : s.pkiDir;
  config.client.trustAnyServer = s.trustAnyServer;
  config.client.user = s.user;
  config.client.password = s.password;
  config.client.timeoutNs = s.timeoutNs;
  config.pollNs = s.pollNs;
  config.subscribe = s.subscribe;
  config.faultOnLoss = s.faultOnLoss;
  config.disconnectWhenStopped = s.disconnectWhenStopped;
  config.report = [](const std::string& line) { std::cerr << line << "\n"; };
  // A node `nodes:` names is wanted even where the wiring by prefix makes its port optional.
  for (const cell::ExternalWire& w : s.wires)
    config.signals.push_back({opcuaNodeOf(s, w.variable), w.variable, w.port, w.tag, w.dir == plant::PortDir::Out,
                              w.optional && !namedNode(s, w.variable)});
  ua::ClientBridge::StartReport report;
  auto bridge = ua::ClientBridge::start(config, cell.bus, report);
  Diagnostics diags;
  bool linked = true;
  for (const auto& p : report.problems) {
    if (p.signal == ua::ClientBridge::kNoSignal) {
      diags.error(celldiag::C034, s.endpointLoc, p.text);
      linked = false;
      continue;
    }
    const bool unknown = p.kind == ua::ClientBridge::Problem::Kind::Unknown;
    const cell::OpcuaNodeName* named = namedNode(s, s.wires[p.signal].variable);
    diags.error(unknown ? celldiag::C032 : celldiag::C033, named ? named->loc : s.wires[p.signal].loc, p.text);
  }
  if (linked)
    reportUnmatchedPrefixes(s.wires, report.found, diags, [&s](const cell::ExternalWire& w, const std::string& device, const std::string& prefix) {
      return "opcua: no port of '" + device + "' matches a node under '" + prefix + "' on " + s.url + " (expected e.g. " +
             opcuaNodeOf(s, w.variable) + ")";
    });
  if (diags.hasErrors() || !bridge) {
    diags.sortByLocation();
    std::cerr << diags.render(sources);
    return nullptr;
  }
  size_t wired = 0;
  for (size_t i = 0; i < s.wires.size(); ++i) wired += report.found[i] && !s.wires[i].port.empty();  // found: one per wire after a start
  std::cerr << "opcua: " << bridge->peerText() << " " << role << " (" << wired << " signals, " << bridge->updatesText() << ")\n";
  return bridge;
}

}  // namespace virtcom::cli
