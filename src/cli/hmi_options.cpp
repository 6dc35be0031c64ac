#include "cli/hmi_options.hpp"

#include <iostream>
#include <random>

namespace virtcom::cli {

namespace {

constexpr uint32_t kLoopbackNet = 0x7f000000;  // 127.0.0.0/8

bool isLoopback(uint32_t ipv4) { return (ipv4 & 0xff000000u) == kLoopbackNet; }

// 128 random bits as hex: the write token when none was given.
std::string randomToken() {
  std::random_device random;
  std::string token;
  static constexpr char kHex[] = "0123456789abcdef";
  for (int i = 0; i < 32; ++i) token += kHex[random() & 15];
  return token;
}

// `before` then `then`, for a scan hook that another server (ADS) may have set already.
std::function<void(plc::Runtime&)> chain(std::function<void(plc::Runtime&)> before, std::function<void(plc::Runtime&)> then) {
  if (!before) return then;
  return [before = std::move(before), then = std::move(then)](plc::Runtime& plc) {
    before(plc);
    then(plc);
  };
}

}  // namespace

void addHmiOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag) {
  cmd->add_option(listenFlag, o.listen,
                  "serve the web HMI (live layout, Gantt, KPIs, watch table, controls) on HOST:PORT, e.g. 127.0.0.1:8080 "
                  "(port 0: a free port, printed; see docs/hmi.md)");
  cmd->add_option("--http-allow", o.allow, "comma-separated IPv4 peers allowed to use the HMI (needed to bind beyond loopback)");
  cmd->add_flag("--allow-any-peer", o.anyPeer, "let every peer use an HMI bound beyond loopback (instead of --http-allow)");
  cmd->add_option("--hmi-token", o.token, "token that HMI writes, forces, faults and controls need (Authorization: Bearer TOKEN)");
  cmd->add_flag("--hmi-readonly", o.readOnly, "the HMI only watches: writes, forces, faults and controls are refused (403)");
  cmd->add_flag("--hmi-paused", o.paused, "start paused: the first tick waits for run or step from the HMI");
}

std::expected<HmiBinding, std::string> checkHmiOptions(const HmiServeOptions& o, const std::string& listenFlag) {
  HmiBinding b;
  auto at = parseEndpoint(o.listen);
  if (!at) return std::unexpected(listenFlag + ": " + at.error());
  b.at = *at;
  if (!o.allow.empty()) {
    auto peers = parseAllowList(o.allow);
    if (!peers) return std::unexpected("--http-allow: " + peers.error());
    b.allowedPeers = *peers;
  }
  b.access.readOnly = o.readOnly;
  b.access.token = o.token;
  if (!isLoopback(b.at.ipv4)) {
    if (b.allowedPeers.empty() && !o.anyPeer)
      return std::unexpected(listenFlag + ": " + formatIpv4(b.at.ipv4) +
                             " is reachable beyond this machine: name the browsers' addresses with --http-allow A,B (or "
                             "--allow-any-peer), or bind 127.0.0.1");
    if (b.access.token.empty() && !o.readOnly) {
      b.access.token = randomToken();
      b.tokenGenerated = true;
    }
  }
  return b;
}

LiveHmi::LiveHmi(cell::Cell& cell, const std::atomic<bool>* interrupt, bool paused, sim::SimOptions& options)
    : cell_(cell), live_(cell, interrupt, paused) {
  options.traceSinks.push_back(&live_);
  options.control = &live_;
  if (cell.module) {
    options.beforeScan = chain(std::move(options.beforeScan), [this](plc::Runtime& plc) { live_.beforeScan(plc); });
    options.afterScan = chain(std::move(options.afterScan), [this](plc::Runtime& plc) { live_.afterScan(plc); });
  }
}

std::expected<void, std::string> LiveHmi::serve(const HmiBinding& binding, sim::Simulation& simulation) {
  int64_t baseTickNs = simulation.hasPlc() ? simulation.plc().baseTickNs() : cell_.run.plcCycleNs;
  api_ = std::make_unique<hmi::Api>(cell_, live_, baseTickNs, binding.access);
  auto server = hmi::HttpServer::start(*api_, binding.at, binding.allowedPeers);
  if (!server) return std::unexpected(server.error());
  server_ = std::move(*server);
  std::cerr << "hmi: serving http://" << formatEndpoint(server_->bound()) << "/ ("
            << (binding.access.readOnly ? "read-only" : binding.access.token.empty() ? "loopback, writes allowed" : "writes need the token")
            << ")\n";
  if (binding.tokenGenerated) std::cerr << "hmi: write token " << binding.access.token << "\n";
  return {};
}

void LiveHmi::stop() {
  if (server_) server_->stop();
}

}  // namespace virtcom::cli
