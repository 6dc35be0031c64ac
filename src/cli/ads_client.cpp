#include "cli/ads_client.hpp"

#include <iostream>

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cli {

std::unique_ptr<proto::ads::ClientBridge> startAdsBridge(cell::Cell& cell, const SourceManager& sources, const std::string& role) {
  namespace ads = proto::ads;
  const cell::AdsClientSettings& s = *cell.plcAds;
  ads::BridgeConfig config;
  config.client.router = s.router;
  config.client.target = {s.netId, s.port};
  config.client.localNetId = s.localNetId;
  config.client.timeoutNs = s.timeoutNs;
  config.faultOnLoss = s.faultOnLoss;
  config.disconnectWhenStopped = s.disconnectWhenStopped;
  config.report = [](const std::string& line) { std::cerr << line << "\n"; };
  for (const cell::ExternalWire& w : s.wires)
    config.signals.push_back({w.variable, w.port, w.tag, w.dir == plant::PortDir::Out, w.optional});
  ads::ClientBridge::StartReport report;
  auto bridge = ads::ClientBridge::start(config, cell.bus, report);
  Diagnostics diags;
  bool linked = true;
  for (const auto& p : report.problems) {
    if (p.signal == ads::ClientBridge::kNoSignal) {
      diags.error(celldiag::C034, s.addressLoc, p.text);
      linked = false;
      continue;
    }
    const bool unknown = p.kind == ads::ClientBridge::Problem::Kind::Unknown;
    diags.error(unknown ? celldiag::C032 : celldiag::C033, s.wires[p.signal].loc, p.text);
  }
  // Wiring by prefix: each such device needs at least one port whose variable the PLC has.
  for (size_t i = 0; linked && i < s.wires.size(); ++i) {
    const cell::ExternalWire& w = s.wires[i];
    if (w.prefixGroup < 0 || (i > 0 && s.wires[i - 1].prefixGroup == w.prefixGroup)) continue;  // a group's first port
    bool any = false;
    for (size_t j = i; j < s.wires.size() && s.wires[j].prefixGroup == w.prefixGroup; ++j) any |= report.found[j];
    if (any) continue;
    std::string device = w.port.substr(0, w.port.find('.'));
    std::string prefix = w.variable.substr(0, w.variable.size() - (w.port.size() - device.size()));
    diags.error(celldiag::C030, w.loc, "ads: no port of '" + device + "' matches a variable under '" + prefix + "' on the PLC at " + s.address +
                                   " (expected e.g. " + w.variable + ")");
  }
  if (diags.hasErrors()) {
    diags.sortByLocation();
    std::cerr << diags.render(sources);
    return nullptr;
  }
  size_t wired = 0;
  for (size_t i = 0; i < s.wires.size(); ++i) wired += report.found[i] && !s.wires[i].port.empty();
  std::cerr << "ads: " << bridge->peerText() << " " << role << " (" << wired << " signals by handle, every step)\n";
  return bridge;
}

}  // namespace virtcom::cli
