// `virtcom serve`: run a cell paced to the wall clock with an external PLC as its controller,
// reached through protocol servers (Modbus TCP), until SIGINT/SIGTERM.
//
// A protocol plugs in with an option group in addServeCommand(), a start function returning a
// BusBridge over the cell's tag bus, and one line in startServers().
#include <atomic>
#include <climits>
#include <csignal>
#include <expected>
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "proto/modbus/signal_server.hpp"
#include "report/kpis.hpp"
#include "report/summary.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

namespace {

std::atomic<bool> gServeStop{false};
extern "C" void onServeSignal(int) { gServeStop = true; }

struct ServeOptions {
  std::string cellFile;
  double speed = 1;
  bool quiet = false;
  std::string modbus;       // HOST:PORT; empty: no Modbus server
  std::string modbusAllow;  // comma-separated peer addresses; empty: any
};

using Bridges = std::vector<std::unique_ptr<BusBridge>>;

std::expected<std::unique_ptr<BusBridge>, std::string> startModbus(const ServeOptions& o, const cell::Cell& cell) {
  namespace mb = proto::modbus;
  auto endpoint = mb::parseEndpoint(o.modbus);
  if (!endpoint) return std::unexpected("--modbus: " + endpoint.error());
  mb::ServerConfig config;
  config.listen = *endpoint;
  if (!o.modbusAllow.empty()) {
    auto allow = mb::parseAllowList(o.modbusAllow);
    if (!allow) return std::unexpected("--modbus-allow: " + allow.error());
    config.allowedPeers = *allow;
  }
  auto server = mb::SignalServer::start(config, cell.modbus);
  if (!server) return std::unexpected("--modbus: " + server.error());
  std::cerr << "modbus: serving on " << mb::formatEndpoint((*server)->endpoint()) << " (" << cell.modbus.entries.size()
            << " signals of " << cell.name << (cell.modbus.automatic ? ", automatic map: see virtcom modbus-map" : "") << ")\n";
  return std::unique_ptr<BusBridge>(std::move(*server));
}

std::expected<Bridges, std::string> startServers(const ServeOptions& o, const cell::Cell& cell) {
  Bridges bridges;
  if (!o.modbus.empty()) {
    auto b = startModbus(o, cell);
    if (!b) return std::unexpected(b.error());
    bridges.push_back(std::move(*b));
  }
  if (bridges.empty()) return std::unexpected(std::string("nothing to serve: give --modbus HOST:PORT"));
  return bridges;
}

int serveCell(const ServeOptions& o) {
  SourceManager sources;
  auto cell = loadCellFile(o.cellFile, sources);
  if (!cell) return kExitCompileError;
  // The external PLC is the controller: the cell's own one (soft PLC or client bridge) stays off.
  if (cell->module) std::cerr << "serve: the soft PLC of " << cell->name << " does not run; the external PLC drives the devices\n";
  cell::detachSoftPlc(*cell);
  // Serving lasts until interrupted; a device error or collision is for the PLC to handle.
  cell->run.stopOnDeviceError = false;
  cell->run.stopOnCollision = false;
  // Handlers first: a client may send SIGTERM as soon as a server announces itself.
  std::signal(SIGINT, onServeSignal);
  std::signal(SIGTERM, onServeSignal);
  auto bridges = startServers(o, *cell);
  if (!bridges) {
    std::cerr << "error: " << bridges.error() << "\n";
    return kExitUsage;
  }
  sim::SimOptions options;
  options.speed = o.speed;
  options.interrupt = &gServeStop;
  options.timeLimitNs = INT64_MAX;
  for (auto& b : *bridges) options.bridges.push_back(b.get());
  sim::Simulation simulation(*cell, options);
  simulation.run();
  bridges->clear();  // stops the servers before the report
  const Trace& trace = simulation.trace();
  if (!o.quiet) std::cout << report::summaryTable(trace, report::computeKpis(trace));
  return kExitOk;
}

}  // namespace

void addServeCommand(CLI::App& app, std::function<void(int)> setExit) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve", "Run a cell paced to the wall clock and serve its device signals to an external PLC (Modbus TCP) until SIGINT/SIGTERM");
  cmd->add_option("cell", o->cellFile, "the cell file (YAML); its 'modbus:' section maps the signals (default: automatic)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--modbus", o->modbus, "serve the signals over Modbus TCP on HOST:PORT (e.g. 127.0.0.1:1502; see docs/modbus.md)");
  cmd->add_option("--modbus-allow", o->modbusAllow, "comma-separated IPv4 peers allowed to connect to --modbus (default: any)");
  cmd->add_option("--speed", o->speed, "pace factor against the wall clock (default 1 = real time)")->check(CLI::PositiveNumber);
  cmd->add_flag("--quiet", o->quiet, "do not print the summary table when stopped");
  cmd->callback([o, setExit] { setExit(serveCell(*o)); });
}

}  // namespace virtcom::cli
