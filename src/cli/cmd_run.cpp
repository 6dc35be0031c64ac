// `virtcom run`: simulate a cell (PLC program + devices) and report cycle time, Gantt, energy.
#include <algorithm>
#include <bit>
#include <chrono>
#include <fstream>
#include <iostream>
#include <optional>
#include <thread>

#include "bytecode/coverage.hpp"
#include "cell/cell.hpp"
#include "cli/commands.hpp"
#include "cli/ads_client.hpp"
#include "cli/audit_options.hpp"
#include "cli/opcua_client.hpp"
#include "cli/common.hpp"
#include "cli/coverage_options.hpp"
#include "cli/plc_backend.hpp"
#include "cli/hmi_options.hpp"
#include "cli/history_options.hpp"
#include "cli/modbus_options.hpp"
#include "cli/rule_trace.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "plc/audited_variables.hpp"
#include "proto/ads/client_bridge.hpp"
#include "proto/modbus/client_bridge.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/summary.hpp"
#include "report/waveform.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

namespace {

struct RunOptions {
  std::string cellFile;
  std::string html, json, vcd, csv;
  std::string until;
  std::string timeLimit;
  std::vector<std::string> sets;
  std::vector<std::string> signals;
  double speed = 0;
  bool quiet = false;
  bool step = false;
  bool traceRules = false;  // print the activity-diagram rules that fired after every PLC tick
  std::string backend = "auto";
  std::string timeMode = "event";  // --time-mode: jump over idle ticks, or step every tick
  size_t traceWindow = kDefaultTraceWindow;
  HmiServeOptions hmi;  // --hmi: watch and steer the run in a browser
  AuditLevel auditWrites = AuditLevel::Summary;  // --audit-writes: the page's writes into the soft PLC
  PeerFlags peers;      // --allow-any-peer
  HistoryRecordOptions history;
  CoverageOptions coverage;
};

// Prints every signal change as it happens (single-step mode).
class ChangePrinter final : public TraceSink {
 public:
  void begin(const Trace& trace) override { trace_ = &trace; }
  void change(const SignalChange& c) override {
    const SignalInfo& s = trace_->signals[c.tag];
    std::cout << "  " << static_cast<double>(c.timeNs) * 1e-9 << " s  " << s.name << " = ";
    if (isFloat(s.type)) std::cout << std::bit_cast<double>(c.raw);
    else if (s.type == ElemType::Bool) std::cout << (c.raw ? "TRUE" : "FALSE");
    else std::cout << static_cast<int64_t>(c.raw);
    std::cout << "\n";
  }
  void end(const Trace&) override {}

 private:
  const Trace* trace_ = nullptr;
};

// Single-step mode: one PLC base tick per line read from stdin (empty line: one tick, a number N:
// N ticks, q: stop); the ChangePrinter among the run's sinks prints every signal that changed.
RunEnd stepInteractively(sim::Simulation& simulation, const Trace& trace) {
  std::cout << "single step: Enter = one tick, N = N ticks, q = quit\n";
  std::string line;
  while (true) {
    std::cout << "[" << static_cast<double>(simulation.nowNs()) * 1e-9 << " s] > " << std::flush;
    if (!std::getline(std::cin, line) || line == "q") break;
    long count = line.empty() ? 1 : std::strtol(line.c_str(), nullptr, 10);
    bool running = true;
    for (long i = 0; i < std::max(count, 1L) && running; ++i) running = simulation.step();
    if (!running) break;
  }
  if (trace.endNs == 0 && simulation.nowNs() > 0) return RunEnd::Interrupted;
  return trace.end;
}

// A file written as the run goes (--vcd, --csv): opened before the run so a bad path is reported
// before any simulation time is spent.
struct StreamedFile {
  std::string path;
  std::ofstream out;
  std::unique_ptr<TraceSink> writer;
};

template <class Writer>
bool openStreamedFile(const std::string& path, std::vector<std::unique_ptr<StreamedFile>>& files) {
  if (path.empty()) return true;
  auto file = std::make_unique<StreamedFile>();
  file->path = path;
  file->out.open(path, std::ios::binary);
  if (!file->out) {
    std::cerr << "error: cannot write " << path << "\n";
    return false;
  }
  file->writer = std::make_unique<Writer>(file->out);
  files.push_back(std::move(file));
  return true;
}

// Flushes the streamed files; false (with a message) if one could not be written completely.
bool closeStreamedFiles(std::vector<std::unique_ptr<StreamedFile>>& files) {
  bool ok = true;
  for (auto& f : files) {
    f->out.close();
    if (!f->out) {
      std::cerr << "error: cannot write " << f->path << "\n";
      ok = false;
    }
  }
  return ok;
}

ExitCode exitCodeFor(RunEnd end) {
  switch (end) {
    case RunEnd::Completed: return ExitCode::Ok;
    case RunEnd::PlcFault: return ExitCode::PlcFault;
    default: return ExitCode::RunStopped;  // device error, collision, time limit, interrupted
  }
}

// After a run watched in the HMI: the page keeps showing its end until the user stops the
// command (false) or resets the run from the page (true).
bool lingerForViewers(LiveHmi& hmi) {
  std::cerr << "hmi: the run has ended; the page stays up until Ctrl-C (or Reset on the page)\n";
  while (!gStopRequested.load()) {
    if (hmi.takeReset()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Why the HMI's reset is refused for this run (null: it is allowed). An external PLC keeps its
// own state, which a reset of the cell cannot bring back; a streamed file holds a single run.
const char* resetRefusal(const cell::Cell& cell, bool streamedFiles) {
  if (cell.externalPlc())
    return "reset is off when an external PLC ('plc: modbus', 'plc: ads' or 'plc: opcua') is the controller: it keeps its own state; "
           "restart the command";
  if (streamedFiles) return "reset is off with --vcd or --csv: the file holds one run; restart the command";
  return nullptr;
}

// The run's summary and report files, after it ended. False if a file could not be written.
bool writeRunOutputs(const RunOptions& o, const cell::Cell& cell, const std::vector<std::string>& timeline,
                     const std::optional<RuleTables>& ruleTables, std::vector<std::unique_ptr<StreamedFile>>& files) {
  const Trace& trace = cell.trace;
  report::Kpis kpis = report::computeKpis(trace);
  // --quiet drops the table, never the reason a run failed.
  if (o.quiet) std::cerr << report::runOutcome(trace, kpis);
  else std::cout << report::summaryTable(trace, kpis);
  report::HtmlOptions html;
  html.title = cell.name;
  // Without --signal the timeline shows what the cell file asked to record.
  html.signals = timeline;
  if (ruleTables) html.diagrams = ruleTables->sections();
  bool ok = closeStreamedFiles(files);
  if (!o.html.empty()) ok = writeFile(o.html, report::htmlReport(trace, kpis, html)) && ok;
  if (!o.json.empty()) ok = writeFile(o.json, report::jsonReport(trace, kpis, html.diagrams)) && ok;
  return ok;
}

ExitCode runCell(const RunOptions& o) {
  std::optional<HmiBinding> hmiBinding;
  if (o.hmi.enabled()) {
    if (o.step) {
      std::cerr << "error: --step and --hmi both step the run: the HMI has its own single step\n";
      return ExitCode::Usage;
    }
    auto binding = checkHmiOptions(o.hmi, o.peers, "--hmi");
    if (!binding) {
      std::cerr << "error: " << binding.error() << "\n";
      return ExitCode::Usage;
    }
    hmiBinding = *binding;
  }
  SourceManager sources;
  auto cell = loadCellFile(o.cellFile, sources, o.coverage.compileOptions());
  if (!cell) return ExitCode::InputError;
  if (!cell->module && !cell->externalPlc()) {
    std::cerr << "error: " << o.cellFile << ": the cell has no controller: add 'plc: sources' (the soft PLC), 'plc: modbus', "
                 "'plc: ads' or 'plc: opcua' (an external PLC), or serve it to a PLC with virtcom serve\n";
    return ExitCode::Usage;
  }
  if (!cell->module && (!o.until.empty() || !o.sets.empty() || o.traceRules || o.coverage.enabled())) {
    std::cerr << "error: --until, --set, --trace-rules and --coverage need the soft PLC, but the controller of " << o.cellFile
              << " is an external PLC\n";
    return ExitCode::Usage;
  }
  if (!o.until.empty()) {
    Diagnostics d;
    cell->run.until = cell::parseCondition(*cell->module, o.until, {}, d);
    if (d.hasErrors()) {
      std::cerr << d.render(sources);
      return ExitCode::Usage;
    }
  }
  sim::SimOptions options;
  std::vector<std::string> plcSources;  // the cell's files: its diagram files are among them
  for (uint32_t file = 0; file < sources.fileCount(); ++file) plcSources.push_back(sources.path(file));
  std::optional<RuleTracer> ruleTracer;
  if (o.traceRules && !(ruleTracer = RuleTracer::load(plcSources, *cell->module))) return ExitCode::Usage;
  // The reports show how often each diagram rule fired: counted after every scan.
  std::optional<RuleTables> ruleTables;
  if (cell->module && (!o.html.empty() || !o.json.empty())) {
    if (!(ruleTables = RuleTables::load(plcSources, *cell->module))) return ExitCode::InputError;
    if (ruleTables->empty()) ruleTables.reset();
  }
  uint64_t scans = 0;
  if (ruleTracer || ruleTables)
    options.afterScan = [&](plc::Runtime& plc) {
      // Debug output the user asked for: printing may allocate, unlike the rest of the scan path.
      if (ruleTracer) ruleTracer->print(scans++, plc.machine().memory(), std::cout);
      if (ruleTables) ruleTables->count(plc);
    };
  options.afterScanSeesJumps = !ruleTracer;  // the counter counts the scans a jump passed over
  options.speed = o.speed;
  options.eventTime = o.timeMode == "event";
  options.interrupt = &gStopRequested;
  std::optional<PlcBackend> backend;
  if (cell->module) {
    backend.emplace(o.backend, *cell->module);
    options.compiled = backend->compiled();
    options.tierUp = backend->tierUp();
  }
  if (!o.timeLimit.empty()) {
    auto ns = parseDurationNs(o.timeLimit);
    if (!ns) {
      std::cerr << "error: --time-limit: '" << o.timeLimit << "' is not a duration (e.g. 300s, 5m)\n";
      return ExitCode::Usage;
    }
    options.timeLimitNs = *ns;
  }
  if (!o.sets.empty()) {
    // Every --set is checked on a scratch image first so mistakes are reported before the run.
    std::vector<uint8_t> scratch(cell->module->memorySize(), 0);
    for (const auto& set : o.sets) {
      std::string problem = presetVariable(*cell->module, set, scratch.data(), nullptr);
      if (!problem.empty()) {
        std::cerr << "error: --set " << problem << "\n";
        return ExitCode::Usage;
      }
    }
    const bc::Module& module = *cell->module;
    options.preset = [&o, &module](plc::Runtime& plc) {
      for (const auto& set : o.sets) presetVariable(module, set, plc.machine().memory(), plc.inputImage());
    };
  }
  std::unique_ptr<proto::modbus::ClientBridge> bridge;
  if (cell->plcModbus) {
    bridge = startClientBridge(*cell->plcModbus, "is the controller");
    options.bridges.push_back(bridge.get());
    if (options.speed == 0) options.speed = 1;  // the external PLC runs in real time
  }
  std::unique_ptr<proto::ads::ClientBridge> adsBridge;
  if (cell->plcAds) {
    adsBridge = startAdsBridge(*cell, sources, "is the controller");
    if (!adsBridge) return ExitCode::InputError;
    options.bridges.push_back(adsBridge.get());
    if (options.speed == 0) options.speed = 1;  // the external PLC runs in real time
  }
  std::unique_ptr<proto::opcua::ClientBridge> opcuaBridge;
  if (cell->plcOpcua) {
    opcuaBridge = startOpcuaBridge(*cell, sources, "is the controller");
    if (!opcuaBridge) return ExitCode::InputError;
    options.bridges.push_back(opcuaBridge.get());
    if (options.speed == 0) options.speed = 1;  // the external PLC runs in real time
  }
  // Only the report's timeline signals stay in memory; files get every change as the run goes.
  std::vector<std::string> timeline = o.signals.empty() ? cell->run.recordVars : o.signals;
  options.keepAllChanges = false;
  options.keptSignals = timeline;
  options.traceWindow = o.traceWindow;
  std::vector<std::unique_ptr<StreamedFile>> files;
  if (!openStreamedFile<report::VcdWriter>(o.vcd, files) || !openStreamedFile<report::CsvWriter>(o.csv, files)) return ExitCode::Usage;
  for (auto& f : files) options.traceSinks.push_back(f->writer.get());
  auto recorder = openRecorder(o.history, *cell, o.cellFile, timeline, options.speed > 0 || hmiBinding.has_value());
  if (!recorder) {
    std::cerr << "error: " << recorder.error() << "\n";
    return ExitCode::HistoryError;
  }
  if (*recorder) options.traceSinks.push_back(recorder->get());
  ChangePrinter printer;
  if (o.step) options.traceSinks.push_back(&printer);
  std::optional<LiveHmi> hmi;
  // The page's writes and forces into the soft PLC, audited as serve audits them.
  std::unique_ptr<WriteAudit> audit;
  if (hmiBinding) {
    hmi.emplace(*cell, &gStopRequested, o.hmi.paused, options);  // paced: speed 1 unless --speed
    hmi->keepHistory(o.history.path);
    if (const char* why = resetRefusal(*cell, !files.empty())) hmi->refuseReset(why);
    if (cell->module) audit = makeWriteAudit(o.auditWrites, plc::auditedVariables(*cell->module), std::cerr, intoTrace(cell, intoRecorder(*recorder)));
    hmi->auditWrites(audit.get());
  }
  stopOnSignals();
  RunEnd end = RunEnd::Completed;
  bool ok = true, historyOk = true;
  CoverageData covered;  // over every run of this command (an HMI reset starts another)
  // One run, or with the HMI one per reset: a reset (during the run, or after its end while the
  // page stays up) starts again from the cell file's initial state, as a new run.
  for (bool first = true;; first = false) {
    {
      sim::Simulation simulation(*cell, options);
      if (hmi && first) {
        if (auto served = hmi->serve(*hmiBinding, simulation, sources); !served) {
          std::cerr << "error: --hmi: " << served.error() << "\n";
          return ExitCode::Usage;
        }
      }
      end = o.step ? stepInteractively(simulation, simulation.trace()) : simulation.run();
      if (backend) backend->logRun(simulation.plc().tierStats());
      if (o.coverage.enabled()) covered.merge(bc::collectCoverage(*cell->module, simulation.plc().machine().memory()));
    }
    bool reset = hmi && hmi->resetRequested();
    if (!reset) {
      if (audit) {
        std::cerr << auditSummary({audit.get()}) << "\n";
        cell->trace.writesAudited = true;
      }
      ok = writeRunOutputs(o, *cell, timeline, ruleTables, files);
      if (hmi) reset = lingerForViewers(*hmi);
    }
    if (!reset) break;
    std::unique_ptr<cell::Cell> fresh;
    while (true) {
      auto reloaded = reloadForReset(*cell, sources, o.coverage.compileOptions());
      if (reloaded) {
        fresh = std::move(*reloaded);
        break;
      }
      std::cerr << "error: hmi: reset: " << reloaded.error() << "\n";
      if (!lingerForViewers(*hmi)) break;  // a later reset tries again (the files may be back as they were)
    }
    if (!fresh) break;
    historyOk = recordNextRun(o.history, *recorder, *fresh, o.cellFile, timeline, true, options.traceSinks) && historyOk;
    hmi->restart(*fresh);
    if (ruleTables) ruleTables->restart();  // the fresh runtime's scans count from 0 again
    cell = std::move(fresh);
    std::cerr << "hmi: reset: the run starts again\n";
  }
  if (hmi) hmi->stop();
  if (o.coverage.enabled()) ok = writeCoverage(o.coverage, covered, cell->name, std::cerr) && ok;
  if (!ok) return ExitCode::Usage;
  if (*recorder && !reportRecording(o.history, **recorder)) return ExitCode::HistoryError;
  if (!historyOk) return ExitCode::HistoryError;
  return exitCodeFor(end);
}

}  // namespace

void addRunCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate a cell file (PLC program + devices) and report cycle time, Gantt chart and energy");
  cmd->add_option("cell", o->cellFile, "the cell file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--report", o->html, "write the HTML report (Gantt chart, KPIs, signals; the rule tables of activity diagrams with their rule firings) to this file");
  cmd->add_option("--json", o->json, "write the JSON report (docs/report.md) to this file");
  cmd->add_option("--vcd", o->vcd, "write every signal change as VCD (GTKWave) to this file");
  cmd->add_option("--csv", o->csv, "write every signal change as CSV to this file");
  cmd->add_option("--until", o->until, "stop when a PLC condition holds, e.g. \"MAIN.partsDone >= 3\"");
  cmd->add_option("--time-limit", o->timeLimit, "virtual time limit, e.g. 300s (overrides run.time_limit)");
  cmd->add_option("--set", o->sets, "NAME=VALUE set in the PLC before its first scan (repeatable), e.g. MAIN.sequence=3");
  cmd->add_option("--signal", o->signals, "signal shown in the report's timeline (repeatable), e.g. Robot1.busy; default: the cell's run.record variables");
  cmd->add_option("--speed", o->speed, "pace to the wall clock (1 = real time); default: as fast as possible (1 with 'plc: modbus', 'plc: ads' or --hmi)")
      ->check(CLI::PositiveNumber);
  addBackendOption(*cmd, o->backend);
  cmd->add_option("--time-mode", o->timeMode,
                  "event (default): jump over ticks in which nothing can change; tick: step every base tick. "
                  "Results are identical (docs/report.md)")
      ->check(CLI::IsMember({"event", "tick"}));
  addTraceWindowOption(*cmd, o->traceWindow);
  addHistoryOptions(cmd, o->history);
  addCoverageOptions(*cmd, o->coverage);
  cmd->add_flag("--quiet", o->quiet, "do not print the summary table (the faults and how the run ended still go to stderr)");
  cmd->add_flag("--step", o->step, "single step: advance one PLC tick per line read from stdin, printing changed signals");
  addHmiOptions(cmd, o->hmi, "--hmi");
  addAuditOption(cmd, o->auditWrites);
  addPeerFlags(cmd, o->peers, false);
  cmd->add_flag("--trace-rules", o->traceRules,
                "print the activity-diagram rules whose IF held, after every PLC tick: scan N  Supply rule 3 fired: Valve := FALSE");
  cmd->callback([o, setExit] { setExit(runCell(*o)); });
}

}  // namespace virtcom::cli
