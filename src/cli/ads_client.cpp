#include "cli/ads_client.hpp"

#include <iostream>

#include "cli/external_wires.hpp"
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
  if (linked)
    reportUnmatchedPrefixes(s.wires, report.found, diags, [&s](const cell::ExternalWire& w, const std::string& device, const std::string& prefix) {
      return "ads: no port of '" + device + "' matches a variable under '" + prefix + "' on the PLC at " + s.address + " (expected e.g. " +
             w.variable + ")";
    });
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
