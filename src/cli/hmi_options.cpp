#include "cli/hmi_options.hpp"

#include <iostream>
#include <random>

#include "cli/common.hpp"
#include "cli/rule_trace.hpp"

namespace virtcom::cli {

namespace {

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

void addHttpOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag, const std::string& what) {
  cmd->add_option(listenFlag, o.listen, what + " on HOST:PORT, e.g. 127.0.0.1:8080 (port 0: a free port, printed; see docs/hmi.md)");
  cmd->add_option("--http-allow", o.allow,
                  "comma-separated IPv4 peers (ADDRESS or ADDRESS/BITS) allowed to use the HMI (needed to bind beyond loopback; see "
                  "docs/security.md)");
}

void addHmiOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag) {
  addHttpOptions(cmd, o, listenFlag, "serve the web HMI (live layout, Gantt, KPIs, watch table, controls)");
  cmd->add_option("--hmi-token", o.token, "token that HMI writes, forces, faults and controls need (Authorization: Bearer TOKEN)");
  cmd->add_flag("--hmi-readonly", o.readOnly, "the HMI only watches: writes, forces, faults and controls are refused (403)");
  cmd->add_flag("--hmi-paused", o.paused, "start paused: the first tick waits for run or step from the HMI");
}

std::expected<HmiBinding, std::string> checkHmiOptions(const HmiServeOptions& o, const PeerFlags& peers, const std::string& listenFlag) {
  HmiBinding b;
  auto at = parseEndpoint(o.listen);
  if (!at) return std::unexpected(listenFlag + ": " + at.error());
  b.at = *at;
  auto policy = peerPolicy(b.at, peers, "http", listenFlag, "--http-allow", o.allow);
  if (!policy) return std::unexpected(policy.error());
  b.peers = std::move(*policy);
  b.access.readOnly = o.readOnly;
  b.access.token = o.token;
  if (!proto::net::isLoopback(b.at.ipv4)) {
    if (b.access.token.empty() && !o.readOnly) {
      b.access.token = randomToken();
      b.tokenGenerated = true;
    }
  }
  return b;
}

LiveHmi::LiveHmi(cell::Cell& cell, const std::atomic<bool>* interrupt, bool paused, sim::SimOptions& options)
    : cell_(&cell), live_(cell, interrupt, paused) {
  options.traceSinks.push_back(&live_);
  options.control = &live_;
  if (cell.module) {
    options.beforeScan = chain(std::move(options.beforeScan), [this](plc::Runtime& plc) { live_.beforeScan(plc); });
    options.afterScan = chain(std::move(options.afterScan), [this](plc::Runtime& plc) { live_.afterScan(plc); });
  }
}

std::expected<void, std::string> LiveHmi::serve(const HmiBinding& binding, sim::Simulation& simulation, const SourceManager& sources) {
  int64_t baseTickNs = simulation.hasPlc() ? simulation.plc().baseTickNs() : cell_->run.plcCycleNs;
  std::vector<hmi::RuleInfo> rules;
  if (cell_->module) {
    std::vector<std::string> files;
    for (uint32_t file = 0; file < sources.fileCount(); ++file) files.push_back(sources.path(file));
    std::vector<plc::CountedRule> counted;
    for (WatchedRule& w : findWatchedRules(files, *cell_->module).value_or(std::vector<WatchedRule>{})) {
      rules.push_back({std::move(w.rule.diagram), std::move(w.rule.index), std::move(w.rule.luType), std::move(w.rule.then)});
      counted.push_back(w.counted);
    }
    live_.watchRules(std::move(counted), cell_->module->tasks.size());
  }
  api_ = std::make_unique<hmi::Api>(*cell_, live_, baseTickNs, binding.access, std::move(rules));
  if (!resetRefusal_.empty()) api_->refuseReset(resetRefusal_);
  if (mirror_) api_->showSteps(mirror_->steps());
  if (!historyPath_.empty()) {
    auto history = hmi::HistoryApi::open(historyPath_);
    if (!history) return std::unexpected("--history: " + history.error());
    history_ = std::move(*history);
    api_->attachHistory(*history_, false);
  }
  auto server = hmi::HttpServer::start(*api_, binding.at, binding.peers);
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

namespace {

// Whether two compilations of the PLC files gave the same program: its code, memory image and
// variables (names, types, addresses).
bool sameProgram(const bc::Module& a, const bc::Module& b) {
  if (a.staticSize != b.staticSize || a.code.size() != b.code.size() || a.initialImage != b.initialImage ||
      a.constants != b.constants || a.symbols.size() != b.symbols.size())
    return false;
  for (size_t i = 0; i < a.symbols.size(); ++i)
    if (a.symbols[i].name != b.symbols[i].name || a.symbols[i].address != b.symbols[i].address || a.symbols[i].type != b.symbols[i].type)
      return false;
  return true;
}

// The fresh cell's devices and signals are the running one's. The running cell's bus may have
// more signals: the simulation adds the recorded PLC variables, and will add them to the fresh
// one in the same order.
bool sameDevices(const cell::Cell& fresh, const cell::Cell& running) {
  if (fresh.devices.size() != running.devices.size() || fresh.bus.size() > running.bus.size()) return false;
  for (size_t i = 0; i < fresh.devices.size(); ++i)
    if (fresh.devices[i]->name() != running.devices[i]->name() || fresh.devices[i]->type() != running.devices[i]->type()) return false;
  for (TagId id = 0; id < fresh.bus.size(); ++id)
    if (fresh.bus.name(id) != running.bus.name(id) || fresh.bus.type(id) != running.bus.type(id)) return false;
  return true;
}

}  // namespace

std::expected<std::unique_ptr<cell::Cell>, std::string> reloadForReset(cell::Cell& running, SourceManager& sources,
                                                                       st::CompileOptions plcOptions) {
  const std::string path = running.file.string();
  auto fresh = loadCellFile(path, sources, plcOptions);
  if (!fresh) return std::unexpected(path + " no longer loads (see above): restart the command");
  const bool samePlc = (fresh->module == nullptr) == (running.module == nullptr) &&
                       (!fresh->module || sameProgram(*fresh->module, *running.module));
  if (!samePlc || !sameDevices(*fresh, running))
    return std::unexpected(path + " or its PLC files changed since the start: the HMI shows the cell it started with; restart the command");
  fresh->module = std::move(running.module);
  fresh->run = running.run;
  return fresh;
}

}  // namespace virtcom::cli
