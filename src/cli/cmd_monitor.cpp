// `virtcom monitor`: the cell model and its HMI watching the real plant (docs/monitor.md). No
// device is simulated: every wired PLC variable of the cell (commands and feedback alike) is
// read from the real controller each poll onto the cell's tag bus, over ADS or OPC UA (the
// wiring's variables) or Modbus TCP (the cell's Modbus map); one loop watches any link. The devices'
// operations are recognised from their handshake (sim/operation_recogniser.hpp) and recorded
// as a simulated run's would be, so the HMI, the reports and the summary work unchanged. The
// digital shadow: the cell model, run once in virtual time at start-up, predicts each
// operation's duration; a completed operation beyond the deviation threshold is an alert. Over
// ADS the position of the program's SFC charts is read too (cli/sfc_mirror.hpp).
#include <climits>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/ads_client.hpp"
#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/history_options.hpp"
#include "cli/hmi_options.hpp"
#include "cell/opcua_settings.hpp"
#include "cli/modbus_options.hpp"
#include "cli/opcua_client.hpp"
#include "cli/opcua_options.hpp"
#include "cli/sfc_mirror.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/production.hpp"
#include "report/summary.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

namespace {

struct MonitorOptions {
  std::string cellFile;
  std::string ads;          // HOST:PORT of the PLC's AMS router
  std::string modbus;       // HOST:PORT of the PLC's Modbus TCP server (instead of --ads)
  std::string opcua;        // opc.tcp://HOST:PORT of the PLC's OPC UA server (instead of --ads)
  std::string netId;        // the PLC's AmsNetId; empty: the cell's, or 127.0.0.1.1.1
  std::string poll = "10ms";
  double deviationPercent = 20;
  std::string json;
  bool quiet = false;
  size_t traceWindow = kDefaultTraceWindow;
  HmiServeOptions hmi;
  OpcuaServeOptions served;  // --serve-opcua: the watched devices' signals over OPC UA, read only
  PeerFlags peers;  // --allow-any-peer
  HistoryRecordOptions history;
};

// The variables a watch over ADS or OPC UA reads from the real PLC when the cell's controller is
// its soft PLC: every wire by its variable name, `cycle_done` (its tag, returned) and the
// `record` variables (the cycle tag unchanged without `cycle_done`). All are read, none written.
TagId watchSoftPlcVariables(cell::Cell& cell, std::vector<cell::ExternalWire>& wires) {
  for (const cell::Wire& w : cell.wires) wires.push_back({w.tag, plant::PortDir::In, w.varName, cell.bus.name(w.tag), {}, false, -1});
  TagId cycleTag = cell.run.cycleDoneTag;
  if (!cell.run.cycleDoneVar.empty()) {
    cycleTag = cell.bus.find(cell.run.cycleDoneVar);  // a Modbus map's cycle_done has given it one
    if (cycleTag == kNoTag) cycleTag = cell.bus.add(cell.run.cycleDoneVar, ElemType::Bool);
    wires.push_back({cycleTag, plant::PortDir::In, cell.run.cycleDoneVar, {}, {}, false, -1});
  }
  for (const auto& name : cell.run.recordVars) wires.push_back({kNoTag, plant::PortDir::In, name, {}, {}, false, -1});
  return cycleTag;
}

// Makes the read-only link `watch` (ADS or OPC UA settings) the cell's controller in `slot`:
// every wire only read, a lost link the end of the watch, the soft PLC detached.
template <typename Settings>
void becomeTheController(cell::Cell& cell, std::optional<Settings>& slot, Settings watch, TagId cycleTag) {
  for (cell::ExternalWire& w : watch.wires) w.dir = plant::PortDir::In;  // the monitor never writes to the PLC
  watch.faultOnLoss = true;
  cell::detachSoftPlc(cell);
  slot = std::move(watch);
  cell.run.cycleDoneTag = cycleTag;
}

// The cell's wiring as variables to read from the real PLC: the soft PLC's wires by their
// variable names (or a `plc: ads:` cell's own), and the steps of the program's charts
// (`mirror`). Replaces the cell's controller by that read-only link.
std::expected<void, std::string> watchOverAds(cell::Cell& cell, const MonitorOptions& o, const SfcMirror& mirror) {
  auto router = parseEndpoint(o.ads);
  if (!router) return std::unexpected("--ads: " + router.error());
  cell::AdsClientSettings watch = cell.plcAds.value_or(cell::AdsClientSettings{});
  watch.address = o.ads;
  watch.router = *router;
  if (!o.netId.empty()) {
    auto id = parseNetId(o.netId);
    if (!id) return std::unexpected("--netid: " + id.error());
    watch.netId = *id;
  }
  TagId cycleTag = cell.run.cycleDoneTag;  // `plc: ads:`: the loader's
  if (!cell.plcAds) {
    cycleTag = watchSoftPlcVariables(cell, watch.wires);
    mirror.addWires(watch.wires);
  }
  becomeTheController(cell, cell.plcAds, std::move(watch), cycleTag);
  return {};
}

// The same over OPC UA: a `plc: opcua:` cell's own wiring and node names, else the soft PLC's
// variables under the CODESYS-form prefix (ns=4;s=|var|virtcom.Application.), which a CODESYS
// PLC or `virtcom exec --opcua` serves them as. Each poll is one Read of every node.
std::expected<void, std::string> watchOverOpcua(cell::Cell& cell, const MonitorOptions& o, int64_t pollNs) {
  auto server = cell::opcuaServerOf(o.opcua);
  if (!server) return std::unexpected("--opcua: " + server.error());
  cell::OpcuaClientSettings watch = cell.plcOpcua.value_or(cell::OpcuaClientSettings{});
  watch.url = o.opcua;
  watch.server = *server;
  watch.pollNs = pollNs;
  // One Read a poll, never a subscription: the operations are recognised from one image of the
  // PLC per poll, as over ADS; a subscription's notifications come item by item and keep only
  // the last value of each, so a short handshake could be merged away or seen out of order.
  watch.subscribe = false;
  TagId cycleTag = cell.run.cycleDoneTag;  // `plc: opcua:`: the loader's
  if (!cell.plcOpcua) cycleTag = watchSoftPlcVariables(cell, watch.wires);
  becomeTheController(cell, cell.plcOpcua, std::move(watch), cycleTag);
  return {};
}

// The cell's Modbus map as the PLC's tables to read: `plc: modbus:`'s (the PLC's own addresses),
// else the `modbus:` one (the tables `serve --modbus` serves the cell as), every entry read each
// poll, none written. Replaces the cell's controller by that read-only link. A Modbus PLC has
// no variables by name, so no `record`; cycles are counted when the map places the PLC's cycle
// marker (`modbus: cycle_done:`).
std::expected<cell::ModbusClientSettings, std::string> watchOverModbus(cell::Cell& cell, const MonitorOptions& o, int64_t pollNs) {
  auto peer = parseEndpoint(o.modbus);
  if (!peer) return std::unexpected("--modbus: " + peer.error());
  cell::ModbusClientSettings watch = cell.plcModbus.value_or(cell::ModbusClientSettings{});
  if (!cell.plcModbus) watch.map = cell.modbus;
  watch.address = o.modbus;
  watch.peer = *peer;
  watch.pollNs = pollNs;
  watch.faultOnLoss = true;
  for (auto& e : watch.map.entries) e.dir = modbus_map::SignalDir::Command;  // read by the bridge, never written
  cell::detachSoftPlc(cell);
  cell.run.cycleDoneTag = watch.map.cycleDone;
  cell.plcModbus.reset();
  cell.plcAds.reset();
  return watch;
}

// The read-only link to the plant's PLC (--ads, --opcua or --modbus) over the cell's tag bus; the cell's
// own controller is detached. Null, the problem printed, if it cannot start; `failure` says how.
std::unique_ptr<BusBridge> openLink(cell::Cell& cell, const SourceManager& sources, const MonitorOptions& o, int64_t pollNs,
                                    SfcMirror& mirror, ExitCode& failure) {
  failure = ExitCode::Usage;
  if (!o.modbus.empty()) {
    auto watch = watchOverModbus(cell, o, pollNs);
    if (!watch) {
      std::cerr << "error: " << watch.error() << "\n";
      return nullptr;
    }
    return startClientBridge(*watch, "is watched (read only)");
  }
  if (!o.opcua.empty()) {
    if (auto watched = watchOverOpcua(cell, o, pollNs); !watched) {
      std::cerr << "error: " << watched.error() << "\n";
      return nullptr;
    }
    failure = ExitCode::InputError;
    return startOpcuaBridge(cell, sources, "is watched (read only)");
  }
  if (auto watched = watchOverAds(cell, o, mirror); !watched) {
    std::cerr << "error: " << watched.error() << "\n";
    return nullptr;
  }
  failure = ExitCode::InputError;
  auto bridge = startAdsBridge(cell, sources, "is watched (read only)");
  if (bridge && !mirror.empty())
    std::fprintf(stderr, "monitor: the PLC has %zu of the %zu SFC steps of the cell's program\n", mirror.bind(cell.bus), mirror.steps().size());
  return bridge;
}

// The model's prediction: the cell run once in virtual time with its own soft PLC. Null (and a
// note) when the cell has none.
std::unique_ptr<cell::Cell> runModel(const std::string& cellFile, SourceManager& sources) {
  auto model = loadCellFile(cellFile, sources);
  if (!model) return nullptr;
  if (!model->module) {
    std::cerr << "monitor: " << cellFile << " has no soft PLC ('plc: sources'): operations are not compared with a model\n";
    return nullptr;
  }
  sim::Simulation simulation(*model, {});
  RunEnd end = simulation.run();
  std::fprintf(stderr, "monitor: the model ran %.3f s (%s), %zu operations, cycle %.3f s\n", model->trace.endNs / 1e9, runEndName(end),
               model->trace.activities.size(), (model->trace.cycleEndNs - model->trace.cycleStartNs) / 1e9);
  return model;
}

// Prints the alerts and completed cycles as they come (on the monitor's thread; only when
// something new happened, which is rare next to the polls).
class AlertPrinter final : public TraceSink {
 public:
  explicit AlertPrinter(int64_t modelCycleNs) : modelCycleNs_(modelCycleNs) {}
  void begin(const Trace&) override {}
  void change(const SignalChange&) override {}
  void tick(const Trace& trace, int64_t nowNs) override {
    for (; faults_ < trace.faults.size(); ++faults_) {
      const FaultRecord& f = trace.faults[faults_];
      std::fprintf(stderr, "monitor: alert at %.3f s: %s: %s\n", f.timeNs / 1e9, f.source.c_str(), f.message.c_str());
    }
    if (trace.cyclesCompleted == cycles_) return;
    cycles_ = trace.cyclesCompleted;
    std::fprintf(stderr, "monitor: cycle %u completed at %.3f s (%.3f s; the model %.3f s)\n", cycles_, nowNs / 1e9,
                 (trace.cycleEndNs - trace.cycleStartNs) / 1e9, modelCycleNs_ / 1e9);
  }
  void end(const Trace&) override {}

 private:
  int64_t modelCycleNs_;
  size_t faults_ = 0;
  uint32_t cycles_ = 0;
};

// Serves the devices' signals over OPC UA as the last poll left them (`--serve-opcua`), announced
// once the first poll is published.
class OpcuaPublisher final : public TraceSink {
 public:
  explicit OpcuaPublisher(OpcuaPlcServer& server) : server_(server) {}
  void begin(const Trace&) override {}
  void change(const SignalChange&) override {}
  void tick(const Trace&, int64_t) override {
    server_.publish({});
    if (!announced_) announceOpcuaServer(server_);
    announced_ = true;
  }
  void end(const Trace&) override {}

 private:
  OpcuaPlcServer& server_;
  bool announced_ = false;
};

// Local wall time (ns since 1970-01-01 00:00 local), what the plan's shifts are written in: the
// UTC clock plus the UTC offset at start-up (a change to or from summer time applies from the
// next start).
class LocalWallClock {
 public:
  LocalWallClock() {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    offsetNs_ = localtime_r(&now, &local) ? static_cast<int64_t>(local.tm_gmtoff) * 1'000'000'000 : 0;
  }
  int64_t nowNs() const { return utcNowNs() + offsetNs_; }

 private:
  int64_t offsetNs_ = 0;
};

// Counts the completed cycles (parts) into the planned shift the wall clock is in, every poll.
// With the historian, the current shift's row is handed to its writer thread when a part
// completes, when a shift begins and at least every second (its pro-rated plan), so a killed
// monitor loses at most the last second of production.
class ProductionSink final : public TraceSink {
 public:
  static constexpr int64_t kRowPeriodNs = 1'000'000'000;

  ProductionSink(const ProductionPlan& plan, const LocalWallClock& clock, history::Recorder* recorder)
      : counter_(plan), clock_(clock), recorder_(recorder) {}
  void begin(const Trace&) override {}
  void change(const SignalChange&) override {}
  void tick(const Trace& trace, int64_t) override {
    const int64_t now = clock_.nowNs();
    counter_.update(now, trace.cyclesCompleted);
    if (recorder_) recordCurrentShift(now);
  }
  void end(const Trace& trace) override { counter_.update(clock_.nowNs(), trace.cyclesCompleted); }
  report::ProductionReport report(const Trace& trace) const {
    return report::productionReport(counter_, clock_.nowNs(), trace, trace.endNs);
  }
  // The HMI's view of the current shift, updated in place (the name's storage is reused).
  void progress(hmi::ShiftProgress& p) const {
    const report::ShiftCount* c = counter_.current();
    if (!c) {
      p = {};
      return;
    }
    const PlannedShift& s = counter_.plan().shifts[c->shift];
    p.shift = s.name;
    p.planNow = report::planNow(s, *c, counter_.lastNs());
    p.parts = c->actual;
  }

 private:
  // On the simulation thread: a few words into the recorder's queue, nothing allocated.
  void recordCurrentShift(int64_t now) {
    const report::ShiftCount* c = counter_.current();
    if (!c) return;
    if (c->actual == rowActual_ && c->startNs == rowStartNs_ && now - rowWallNs_ < kRowPeriodNs) return;
    const PlannedShift& s = counter_.plan().shifts[c->shift];
    recorder_->production(c->shift, {c->startNs, c->endNs, c->watchedFromNs, report::planNow(s, *c, now), s.parts, c->actual});
    rowActual_ = c->actual;
    rowStartNs_ = c->startNs;
    rowWallNs_ = now;
  }

  report::ProductionCounter counter_;
  const LocalWallClock& clock_;
  history::Recorder* recorder_;  // null: no historian
  // The row handed over last: its shift occurrence, parts and when.
  int64_t rowStartNs_ = INT64_MIN, rowWallNs_ = 0;
  uint32_t rowActual_ = 0;
};

// The shifts watched, as the historian's `production` rows.
std::vector<history::ProductionRow> productionRows(const report::ProductionReport& r) {
  std::vector<history::ProductionRow> rows;
  for (const auto& s : r.shifts)
    rows.push_back({s.day, s.name, s.startNs, s.endNs, s.watchedFromNs, int64_t{s.plan}, s.planNow, int64_t{s.actual}});
  return rows;
}

// Per (device, operation): runs, mean actual duration, the model's range, the worst deviation.
void printShadow(const Trace& trace, const sim::OperationRecogniser& recogniser) {
  std::printf("\n%-12s %-16s %5s %10s %15s %9s %6s\n", "Device", "Operation", "Runs", "Actual s", "Model s", "Worst", "Alerts");
  for (const sim::OperationStats& s : recogniser.stats()) {
    char model[32] = "-";
    if (s.expected.known() && s.expected.minNs == s.expected.maxNs) std::snprintf(model, sizeof model, "%.3f", s.expected.maxNs / 1e9);
    else if (s.expected.known()) std::snprintf(model, sizeof model, "%.3f-%.3f", s.expected.minNs / 1e9, s.expected.maxNs / 1e9);
    std::printf("%-12s %-16s %5u %10.3f %15s %+8.1f%% %6u\n", trace.devices[s.device].name.c_str(), trace.labels[s.label].c_str(), s.count,
                s.totalNs / 1e9 / s.count, model, s.worstDeviation * 100, s.alerts);
  }
}

ExitCode monitorCell(const MonitorOptions& o) {
  if (o.ads.empty() + o.modbus.empty() + o.opcua.empty() != 2) {
    std::cerr << "error: give the plant's PLC as one of --ads HOST:PORT, --opcua opc.tcp://HOST:PORT or --modbus HOST:PORT\n";
    return ExitCode::Usage;
  }
  auto pollNs = parseDurationNs(o.poll);
  if (!pollNs || *pollNs <= 0) {
    std::cerr << "error: --poll: '" << o.poll << "' is not a positive duration (e.g. 10ms)\n";
    return ExitCode::Usage;
  }
  std::optional<HmiBinding> hmiBinding;
  if (o.hmi.enabled()) {
    // The HMI only watches: there is no soft PLC to write to, no simulated device to fault, and
    // pausing would only stop the polls.
    HmiServeOptions watchOnly = o.hmi;
    watchOnly.readOnly = true;
    auto binding = checkHmiOptions(watchOnly, o.peers, "--http");
    if (!binding) {
      std::cerr << "error: " << binding.error() << "\n";
      return ExitCode::Usage;
    }
    hmiBinding = *binding;
  }
  SourceManager sources;
  auto cell = loadCellFile(o.cellFile, sources);
  if (!cell) return ExitCode::InputError;
  // Watching lasts until interrupted; what the plant does is reported, never stops the watch.
  cell->run.until = {};
  cell->run.cycles = UINT32_MAX;
  cell->run.stopOnDeviceError = false;
  cell->run.stopOnCollision = false;
  cell->run.plcCycleNs = *pollNs;
  stopOnSignals();
  ExitCode linkFailure = ExitCode::Ok;
  // Over ADS, the charts of the cell's program are looked for in the PLC by their step names.
  SfcMirror mirror(!o.ads.empty() ? std::move(cell->module) : nullptr);
  auto bridge = openLink(*cell, sources, o, *pollNs, mirror, linkFailure);
  if (!bridge) return linkFailure;
  // The monitor's own time follows the wall clock: a full queue drops events, never waits.
  auto recorder = openRecorder(o.history, *cell, o.cellFile, cell->run.recordVars, true);
  if (!recorder) {
    std::cerr << "error: " << recorder.error() << "\n";
    return ExitCode::HistoryError;
  }
  auto model = runModel(o.cellFile, sources);
  sim::SimOptions options;
  options.speed = 1;  // the plant's own time
  options.interrupt = &gStopRequested;
  options.timeLimitNs = INT64_MAX;
  options.keepAllChanges = false;  // watches for days: no signal history in memory
  options.traceWindow = o.traceWindow;
  options.bridges.push_back(bridge.get());
  options.watch.enabled = true;
  options.watch.threshold = o.deviationPercent / 100;
  AlertPrinter alerts(model && model->trace.cyclesCompleted > 0 ? model->trace.cycleEndNs - model->trace.cycleStartNs : 0);
  options.traceSinks.push_back(&alerts);
  if (!mirror.empty()) options.traceSinks.push_back(&mirror);  // before the HMI's, which publishes its image
  LocalWallClock wallClock;
  ProductionSink production(cell->plan, wallClock, *recorder && !cell->plan.shifts.empty() ? recorder->get() : nullptr);
  options.traceSinks.push_back(&production);
  if (*recorder) options.traceSinks.push_back(recorder->get());
  std::optional<LiveHmi> hmi;
  if (hmiBinding) {
    hmi.emplace(*cell, &gStopRequested, o.hmi.paused, options);
    hmi->keepHistory(o.history.path);
    hmi->refuseReset("reset is off in monitor: the plant is real and keeps its own state");
  }
  if (hmi && !mirror.empty()) hmi->mirrorSteps(mirror);
  if (hmi && !cell->plan.shifts.empty()) hmi->watchShifts([&production](hmi::ShiftProgress& p) { production.progress(p); });
  std::unique_ptr<OpcuaPlcServer> opcuaServer;
  std::optional<OpcuaPublisher> opcuaPublisher;
  if (o.served.enabled()) {
    OpcuaServeOptions watchOnly = o.served;
    watchOnly.readOnly = true;  // the plant's PLC owns its signals
    auto server = startOpcuaServer(watchOnly, o.peers, nullptr, cell.get());
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    opcuaServer = std::move(*server);
    options.traceSinks.push_back(&opcuaPublisher.emplace(*opcuaServer));
  }
  if (model) options.watch.model = &model->trace;
  sim::Simulation simulation(*cell, options);
  if (hmi) {
    if (auto served = hmi->serve(*hmiBinding, simulation, sources); !served) {
      std::cerr << "error: --http: " << served.error() << "\n";
      return ExitCode::Usage;
    }
  }
  RunEnd end = simulation.run();
  if (hmi) hmi->stop();
  if (opcuaServer) opcuaServer->stop();
  const Trace& trace = cell->trace;
  report::Kpis kpis = report::computeKpis(trace);
  const report::ProductionReport produced = production.report(trace);
  if (!o.quiet) {
    std::cout << report::summaryTable(trace, kpis);
    printShadow(trace, *simulation.recogniser());
    if (!mirror.empty()) std::cout << "\nSFC steps active when stopped: " << (mirror.activeSteps().empty() ? "none" : mirror.activeSteps()) << "\n";
    std::cout << report::productionTable(produced);
  }
  if (!o.json.empty() && !writeFile(o.json, report::jsonReport(trace, kpis, {}, &produced))) return ExitCode::Usage;
  // A failure is kept in the recorder's error(), which reportRecording() prints.
  if (*recorder && !cell->plan.shifts.empty()) (*recorder)->recordProduction(productionRows(produced));
  if (*recorder && !reportRecording(o.history, **recorder)) return ExitCode::HistoryError;
  if (end == RunEnd::PlcFault) {
    std::cerr << "monitor: " << trace.endMessage << "\n";
    return ExitCode::PlcFault;
  }
  return ExitCode::Ok;
}

}  // namespace

void addMonitorCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<MonitorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "monitor", "Watch the real plant through the cell's wiring until SIGINT/SIGTERM: its PLC's variables read over ADS, OPC UA or Modbus TCP, the "
                 "devices' operations recognised and compared with the cell model (digital shadow), optionally in the web HMI");
  cmd->add_option("cell", o->cellFile, "the cell file (YAML) whose wiring names the PLC's variables")->required()->check(CLI::ExistingFile);
  CLI::Option* ads = cmd->add_option("--ads", o->ads, "the PLC's AMS router, HOST:PORT (TwinCAT: 48898; or a virtcom serve --ads)");
  cmd->add_option("--modbus", o->modbus, "instead of --ads: the PLC's Modbus TCP server, HOST:PORT, read through the cell's Modbus map "
                                        "(plc: modbus: map, else the modbus: one; see virtcom modbus-map)")
      ->excludes(ads);
  cmd->add_option("--opcua", o->opcua, "instead of --ads: the PLC's OPC UA server, opc.tcp://HOST:PORT (the cell's plc: opcua: nodes, else "
                                      "the wired variables as ns=4;s=|var|virtcom.Application.VAR, CODESYS' form and virtcom exec --opcua's)")
      ->excludes(ads);
  cmd->add_option("--netid", o->netId, "the PLC's AmsNetId (default: the cell's plc: ads: netid, else 127.0.0.1.1.1)");
  cmd->add_option("--poll", o->poll, "read every wired variable this often (default 10ms; shorter than the shortest handshake pulse)");
  cmd->add_option("--deviation", o->deviationPercent, "alert when an operation's duration deviates from the model's by more than this "
                                                      "many percent (default 20)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--json", o->json, "write the JSON report (docs/report.md) of what was watched to this file when stopped");
  cmd->add_flag("--quiet", o->quiet, "do not print the summary and the model comparison when stopped");
  addTraceWindowOption(*cmd, o->traceWindow);
  addHmiOptions(cmd, o->hmi, "--http");  // always read-only here (--hmi-readonly is implied)
  addOpcuaServeOptions(cmd, o->served, "--serve-opcua",
                       "serve the watched devices' signals over OPC UA (opc.tcp, read only) on HOST:PORT, e.g. 127.0.0.1:4841, as "
                       "`serve --opcua` serves a simulated cell's (docs/monitor.md)");
  addPeerFlags(cmd, o->peers, false);
  addHistoryOptions(cmd, o->history);
  cmd->callback([o, setExit] { setExit(monitorCell(*o)); });
}

}  // namespace virtcom::cli
