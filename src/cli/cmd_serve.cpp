// `virtcom serve`: run a cell paced to the wall clock until SIGINT/SIGTERM and serve it:
//  - `--modbus`: its device signals, to an external PLC that is the controller (Modbus TCP);
//  - `--ads`: its soft PLC, which stays the controller, as a TwinCAT 3 runtime (ADS), the same
//    server as `exec --ads`. With both, the Modbus map serves the device signals for reading,
//    and only the commands the soft PLC does not drive for writing;
//  - `--opcua`: its soft PLC's variables over OPC UA (docs/opcua.md), the same server as
//    `exec --opcua`; the soft PLC stays the controller;
//  - `--http`: the web HMI (docs/hmi.md), watching and steering the run. Alone, or with --ads,
//    the soft PLC is the controller; with --modbus the external PLC is.
//
// A signal protocol plugs in with an option group in addServeCommand(), a start function
// returning a BusBridge over the cell's tag bus, and one line in startServers().
#include <climits>
#include <cstdint>
#include <expected>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/ads_options.hpp"
#include "cli/audit_options.hpp"
#include "cli/opcua_options.hpp"
#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/plc_backend.hpp"
#include "cli/hmi_options.hpp"
#include "cli/history_options.hpp"
#include "cli/modbus_options.hpp"
#include "plc/audited_variables.hpp"
#include "proto/modbus/audited_signals.hpp"
#include "proto/modbus/signal_server.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/summary.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

namespace {

struct ServeOptions {
  std::string cellFile;
  double speed = 1;
  bool quiet = false;
  std::string json;         // the JSON report, written when stopped; empty: none
  std::string modbus;       // HOST:PORT; empty: no Modbus server
  std::string modbusAllow;  // --modbus-allow: comma-separated peers; empty: any (loopback only)
  bool modbusReadOnly = false;
  PeerFlags peers;          // --allow-any-peer and the limits, for every server of the command
  AuditLevel auditWrites = AuditLevel::Summary;  // --audit-writes: ADS, OPC UA and HMI writes into the soft PLC
  AdsServeOptions ads;      // the soft PLC over ADS
  OpcuaServeOptions opcua;  // the soft PLC's variables over OPC UA
  HmiServeOptions hmi;      // the web HMI (--http)
  std::string backend = "auto";
  size_t traceWindow = kDefaultTraceWindow;
  HistoryRecordOptions history;
};

using Bridges = std::vector<std::unique_ptr<BusBridge>>;

std::expected<std::unique_ptr<BusBridge>, std::string> startModbus(const ServeOptions& o, const cell::Cell& cell, WriteAudit* audit) {
  namespace mb = proto::modbus;
  auto settings = modbusServerConfig(o.modbus, o.modbusAllow, o.peers);
  if (!settings) return std::unexpected(settings.error());
  mb::ServerConfig config = *settings;
  config.readOnly = o.modbusReadOnly;
  auto server = mb::SignalServer::start(config, cell.modbus);
  if (!server) return std::unexpected("--modbus: " + server.error());
  (*server)->auditWrites(audit);
  std::cerr << "modbus: serving on " << mb::formatEndpoint((*server)->endpoint()) << " (" << cell.modbus.entries.size()
            << " signals of " << cell.name << (cell.modbus.automatic ? ", automatic map: see virtcom modbus-map" : "") << ")\n";
  return std::unique_ptr<BusBridge>(std::move(*server));
}

std::expected<Bridges, std::string> startServers(const ServeOptions& o, const cell::Cell& cell, WriteAudit* modbusAudit) {
  Bridges bridges;
  if (!o.modbus.empty()) {
    auto b = startModbus(o, cell, modbusAudit);
    if (!b) return std::unexpected(b.error());
    bridges.push_back(std::move(*b));
  }
  return bridges;
}

// With the soft PLC as the controller, the commands it drives through the wiring are its to
// write: the Modbus map serves them read-only, as status.
void keepSoftPlcCommands(cell::Cell& cell) {
  for (auto& e : cell.modbus.entries) {
    if (e.dir != proto::modbus::SignalDir::Command) continue;
    for (const cell::Wire& w : cell.wires)
      if (w.dir == plant::PortDir::In && w.tag == e.tag) {
        e.dir = proto::modbus::SignalDir::Status;
        e.readOnly = true;
      }
  }
}

ExitCode serveCell(const ServeOptions& o) {
  if (o.modbus.empty() && !o.ads.enabled() && !o.opcua.enabled() && !o.hmi.enabled()) {
    std::cerr << "error: nothing to serve: give --modbus HOST:PORT, --ads HOST:PORT, --opcua HOST:PORT and/or --http HOST:PORT\n";
    return ExitCode::Usage;
  }
  std::optional<HmiBinding> hmiBinding;
  if (o.hmi.enabled()) {
    auto binding = checkHmiOptions(o.hmi, o.peers, "--http");
    if (!binding) {
      std::cerr << "error: " << binding.error() << "\n";
      return ExitCode::Usage;
    }
    hmiBinding = *binding;
  }
  SourceManager sources;
  auto cell = loadCellFile(o.cellFile, sources);
  if (!cell) return ExitCode::InputError;
  if (o.ads.enabled() || o.opcua.enabled() || (o.hmi.enabled() && o.modbus.empty())) {
    // The soft PLC is the controller (served over ADS or OPC UA, watched by the HMI); it runs until interrupted.
    if (!cell->module) {
      std::cerr << "error: " << (o.ads.enabled() ? "--ads serves" : o.opcua.enabled() ? "--opcua serves" : "--http without --modbus runs")
                << " the cell's soft PLC, but "
                << o.cellFile << " has none ('plc: sources')\n";
      return ExitCode::Usage;
    }
    cell->run.until = {};
    cell->run.cycles = UINT32_MAX;  // cycles are counted for the summary, never end the run
    keepSoftPlcCommands(*cell);
  } else {
    // The external PLC is the controller: the cell's own one (soft PLC or client bridge) stays off.
    if (cell->module) std::cerr << "serve: the soft PLC of " << cell->name << " does not run; the external PLC drives the devices\n";
    cell::detachSoftPlc(*cell);
  }
  // Serving lasts until interrupted; a device error or collision is for the PLC to handle.
  cell->run.stopOnDeviceError = false;
  cell->run.stopOnCollision = false;
  // Before the servers announce themselves: a history file that cannot be used stops serve first.
  auto recorder = openRecorder(o.history, *cell, o.cellFile, cell->run.recordVars, true);
  if (!recorder) {
    std::cerr << "error: " << recorder.error() << "\n";
    return ExitCode::HistoryError;
  }
  // Handlers first: a client may send SIGTERM as soon as a server announces itself.
  stopOnSignals();
  // The writes of the external PLC (or any Modbus client) into the cell's signals: the same audit
  // as the soft PLC's writes, naming the signals.
  auto modbusAudit = o.modbus.empty() ? nullptr
                                      : makeWriteAudit(o.auditWrites, proto::modbus::auditedSignals(cell->modbus), std::cerr,
                                                       intoTrace(cell, intoRecorder(*recorder)));
  auto bridges = startServers(o, *cell, modbusAudit.get());
  if (!bridges) {
    std::cerr << "error: " << bridges.error() << "\n";
    return ExitCode::Usage;
  }
  std::unique_ptr<proto::ads::PlcServer> ads;
  if (o.ads.enabled()) {
    auto server = startAdsServer(o.ads, o.peers, *cell->module);
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    ads = std::move(*server);
  }
  std::unique_ptr<OpcuaPlcServer> opcua;
  if (o.opcua.enabled()) {
    auto server = startOpcuaServer(o.opcua, o.peers, cell->module.get(), cell.get());
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    opcua = std::move(*server);
  }
  sim::SimOptions options;
  options.speed = o.speed;
  options.interrupt = &gStopRequested;
  options.timeLimitNs = INT64_MAX;
  options.keepAllChanges = false;  // serves for days: no signal history in memory
  options.traceWindow = o.traceWindow;
  for (auto& b : *bridges) options.bridges.push_back(b.get());
  std::optional<PlcBackend> backend;
  if (cell->module) {
    backend.emplace(o.backend, *cell->module);
    options.compiled = backend->compiled();
    options.tierUp = backend->tierUp();
  }
  // A reset (which would replace the module) is refused while these serve.
  // The writes into the soft PLC from outside: its servers' clients and the HMI's page; each
  // record kept in the run's trace for its reports, and into the historian when one records (the
  // recorder in use: a reset replaces it).
  auto audit = cell->module && (ads || opcua || hmiBinding)
                   ? makeWriteAudit(o.auditWrites, plc::auditedVariables(*cell->module), std::cerr, intoTrace(cell, intoRecorder(*recorder)))
                   : nullptr;
  if (ads || opcua) {
    // The first snapshot right after the cold start, then the announcement: a client that
    // connects at once reads the initial values, never an empty image.
    options.preset = [&](plc::Runtime& plc) {
      if (ads) {
        ads->afterScan(plc);
        announceAdsServer(o.ads, *ads);
      }
      if (opcua) {
        opcua->afterScan(plc);
        announceOpcuaServer(*opcua);
      }
    };
    options.beforeScan = [&](plc::Runtime& plc) {
      if (audit) audit->setVirtualTime(plc.nextTickNs());
      if (ads) ads->beforeScan(plc, audit.get());
      if (opcua) opcua->beforeScan(plc, audit.get());
    };
    options.afterScan = [&](plc::Runtime& plc) {
      if (ads) ads->afterScan(plc);
      if (opcua) opcua->afterScan(plc);
    };
  }
  std::optional<LiveHmi> hmi;
  if (hmiBinding) {
    hmi.emplace(*cell, &gStopRequested, o.hmi.paused, options);
    hmi->keepHistory(o.history.path);
    hmi->auditWrites(audit.get());
    if (!o.modbus.empty() || ads || opcua)
      hmi->refuseReset("reset is off while --modbus, --ads or --opcua serve the run: their clients hold the state of the run; restart serve");
  }
  if (*recorder) options.traceSinks.push_back(recorder->get());
  RunEnd end = RunEnd::Completed;
  bool historyOk = true;
  // One run, or one per reset from the HMI (docs/hmi.md): the cell starts again from its file.
  for (bool first = true;; first = false) {
    {
      sim::Simulation simulation(*cell, options);
      if (hmi && first) {
        if (auto served = hmi->serve(*hmiBinding, simulation, sources); !served) {
          std::cerr << "error: --http: " << served.error() << "\n";
          return ExitCode::Usage;
        }
      }
      end = simulation.run();
      if (backend) backend->logRun(simulation.plc().tierStats());
    }
    if (!hmi || !hmi->resetRequested()) break;
    auto fresh = reloadForReset(*cell, sources);
    if (!fresh) {
      std::cerr << "error: hmi: reset: " << fresh.error() << "\n";
      break;
    }
    historyOk = recordNextRun(o.history, *recorder, **fresh, o.cellFile, cell->run.recordVars, true, options.traceSinks) && historyOk;
    hmi->restart(**fresh);
    cell = std::move(*fresh);
    std::cerr << "hmi: reset: the run starts again\n";
  }
  bridges->clear();  // stops the servers before the report
  if (ads) ads->stop();
  if (opcua) opcua->stop();
  if (hmi) hmi->stop();
  if (audit || modbusAudit) {
    std::cerr << auditSummary({audit.get(), modbusAudit.get()}) << "\n";
    cell->trace.writesAudited = true;
  }
  const Trace& trace = cell->trace;
  const report::Kpis kpis = report::computeKpis(trace);
  // --quiet drops the table, never the reason a run failed.
  if (o.quiet) std::cerr << report::runOutcome(trace, kpis);
  else std::cout << report::summaryTable(trace, kpis);
  if (!o.json.empty() && !writeFile(o.json, report::jsonReport(trace, kpis))) return ExitCode::Usage;
  if (*recorder && !reportRecording(o.history, **recorder)) return ExitCode::HistoryError;
  if (!historyOk) return ExitCode::HistoryError;
  if (end == RunEnd::PlcFault) {
    std::cerr << "runtime fault: " << trace.endMessage << "\n";
    return ExitCode::PlcFault;
  }
  return ExitCode::Ok;
}

}  // namespace

void addServeCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve", "Run a cell paced to the wall clock until SIGINT/SIGTERM, serving its device signals to an external PLC (Modbus TCP), "
               "its soft PLC as a TwinCAT runtime (ADS) and/or the web HMI (HTTP)");
  cmd->add_option("cell", o->cellFile, "the cell file (YAML); its 'modbus:' section maps the signals (default: automatic)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--modbus", o->modbus, "serve the signals over Modbus TCP on HOST:PORT (e.g. 127.0.0.1:1502; see docs/modbus.md)");
  addModbusServeOptions(cmd, o->modbusAllow, o->modbusReadOnly);
  addAdsServeOptions(cmd, o->ads);
  addOpcuaServeOptions(cmd, o->opcua);
  addPeerFlags(cmd, o->peers, true);
  addAuditOption(cmd, o->auditWrites);
  addHmiOptions(cmd, o->hmi, "--http");
  cmd->add_option("--speed", o->speed, "pace factor against the wall clock (default 1 = real time)")->check(CLI::PositiveNumber);
  addBackendOption(*cmd, o->backend);
  addTraceWindowOption(*cmd, o->traceWindow);
  addHistoryOptions(cmd, o->history);
  cmd->add_flag("--quiet", o->quiet, "do not print the summary table when stopped (the faults and how the run ended still go to stderr)");
  cmd->add_option("--json", o->json, "write the JSON report (docs/report.md) of the served run to this file when stopped");
  cmd->callback([o, setExit] { setExit(serveCell(*o)); });
}

}  // namespace virtcom::cli
