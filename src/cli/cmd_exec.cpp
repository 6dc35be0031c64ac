// `virtcom exec`: run ST programs on the soft PLC in virtual time (or paced with --speed).
#include <expected>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/ads_options.hpp"
#include "cli/audit_options.hpp"
#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/coverage_options.hpp"
#include "cli/plc_backend.hpp"
#include "cli/modbus_options.hpp"
#include "cli/opcua_options.hpp"
#include "cli/rule_trace.hpp"
#include "bytecode/coverage.hpp"
#include "lang/sfc/step_monitor.hpp"
#include "plc/audited_variables.hpp"
#include "plc/retain_file.hpp"
#include "plc/runtime.hpp"
#include "proto/modbus/server.hpp"
#include "report/summary.hpp"

namespace virtcom::cli {

namespace {

struct ExecOptions {
  std::vector<std::string> files;
  int64_t cycles = -1;
  std::string cycleTime;
  std::vector<std::string> sets;
  std::vector<std::string> prints;
  std::vector<std::string> traces;
  std::string traceFile;
  bool traceSteps = false;  // print the active SFC steps after every scan
  bool traceRules = false;  // print the activity-diagram rules that fired after every scan
  double speed = 0;
  uint64_t budget = 50'000'000;
  bool stats = false;
  std::string modbus;       // HOST:PORT to serve Modbus TCP on; empty: no server
  std::string modbusAllow;  // --modbus-allow: comma-separated peers; empty: any (loopback only)
  bool modbusReadOnly = false;
  PeerFlags peers;          // --allow-any-peer and the limits, for every server of the command
  AuditLevel auditWrites = AuditLevel::Summary;  // --audit-writes
  bool modbusWritableInputs = false;  // %IW also as holding registers 8192.. (docs/modbus.md)
  AdsServeOptions ads;
  OpcuaServeOptions opcua;
  std::string retainFile;   // warm start: RETAIN/PERSISTENT variables loaded from and saved to it
  std::string backend = "auto";
  CoverageOptions coverage;
};

bool resolveAll(const bc::Module& m, const std::vector<std::string>& names, std::vector<bc::VarRef>& out) {
  for (const auto& n : names) {
    auto ref = bc::resolveVariable(m, n);
    if (!ref) {
      std::cerr << "error: unknown variable '" << n << "' (use the qualified name, e.g. MAIN.count or GVL.x)\n";
      return false;
    }
    out.push_back(*ref);
  }
  return true;
}

void writeTraceRow(std::ostream& out, const bc::Module& m, const uint8_t* memory, uint64_t scan, int64_t timeNs,
                   const std::vector<bc::VarRef>& refs) {
  out << scan << ',' << (timeNs / 1'000'000);
  for (const auto& r : refs) {
    std::string v = bc::formatValue(m, r, memory);
    bool quote = v.find_first_of(",\"") != std::string::npos;
    if (quote) {
      std::string q = "\"";
      for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      v = q + "\"";
    }
    out << ',' << v;
  }
  out << '\n';
}

// The soft PLC's process areas as the Modbus server sees them: %I is the external input image
// (what the next scan reads), %Q and %M are the PLC's own memory.
proto::modbus::ImageView modbusView(plc::Runtime& runtime) {
  const bc::Module& m = runtime.module();
  uint8_t* mem = runtime.machine().memory();
  proto::modbus::ImageView view{{runtime.inputImage(), m.inputs.size}, {mem + m.outputs.address, m.outputs.size}, {mem + m.memory.address, m.memory.size}};
  view.plcAddresses = {m.inputs.address, m.outputs.address, m.memory.address, 0};
  return view;
}

std::expected<std::unique_ptr<proto::modbus::Server>, std::string> startModbus(const ExecOptions& o, plc::Runtime& runtime) {
  namespace mb = proto::modbus;
  auto settings = modbusServerConfig(o.modbus, o.modbusAllow, o.peers);
  if (!settings) return std::unexpected(settings.error());
  mb::ServerConfig config = *settings;
  config.readOnly = o.modbusReadOnly;
  const bc::Module& m = runtime.module();
  mb::ImageShape shape;
  shape.inputs = m.inputs.size;
  shape.outputs = m.outputs.size;
  shape.memory = m.memory.size;
  shape.writableInputs = o.modbusWritableInputs;
  auto server = mb::Server::start(config, shape);
  if (!server) return std::unexpected("--modbus: " + server.error());
  (*server)->publishSnapshot(modbusView(runtime));
  return server;
}

ExitCode runExec(const ExecOptions& o) {
  SourceManager sources;
  Diagnostics diags;
  auto module = compileFiles(o.files, sources, diags, true, o.coverage.compileOptions());
  if (!module) return ExitCode::InputError;
  if (!o.cycleTime.empty()) {
    auto ns = parseDurationNs(o.cycleTime);
    if (!ns) {
      std::cerr << "error: --cycle-time: '" << o.cycleTime << "' is not a duration (e.g. 10ms, 1s, 250us)\n";
      return ExitCode::Usage;
    }
    // The cycle time applies to the default task; configured tasks keep their INTERVAL.
    for (auto& t : module->tasks)
      if (t.isDefault) t.intervalNs = *ns;
  }
  std::vector<bc::VarRef> printRefs, traceRefs;
  std::vector<std::string> traceNames;
  for (const auto& group : o.traces) {
    std::stringstream ss(group);
    std::string name;
    while (std::getline(ss, name, ','))
      if (!name.empty()) traceNames.push_back(name);
  }
  if (!resolveAll(*module, o.prints, printRefs) || !resolveAll(*module, traceNames, traceRefs)) return ExitCode::Usage;
  std::vector<sfc::StepVariable> steps;
  std::string activeSteps;
  if (o.traceSteps) {
    steps = sfc::findSteps(*module);
    if (steps.empty()) {
      std::cerr << "error: --trace-steps: the program has no SFC steps (INITIAL_STEP / STEP, see docs/st-dialect.md)\n";
      return ExitCode::Usage;
    }
  }

  std::optional<RuleTracer> ruleTracer;
  if (o.traceRules && !(ruleTracer = RuleTracer::load(o.files, *module))) return ExitCode::Usage;

  std::unique_ptr<Clock> clock;
  // A Modbus server talks to the real world, so it runs in real time unless told otherwise.
  double speed = o.speed > 0 ? o.speed : o.modbus.empty() && !o.ads.enabled() && !o.opcua.enabled() ? 0 : 1;
  PacedClock* paced = nullptr;  // counts the late ticks
  if (speed > 0) {
    auto pacedClock = std::make_unique<PacedClock>(speed);
    paced = pacedClock.get();
    clock = std::move(pacedClock);
  } else {
    clock = std::make_unique<VirtualClock>();
  }
  plc::RuntimeOptions ropts;
  ropts.instructionBudget = o.budget;
  plc::Runtime runtime(*module, *clock, ropts);
  PlcBackend backend(o.backend, *module);
  backend.attach(runtime);
  if (!runtime.coldStart()) {
    std::cerr << "runtime fault: " << runtime.faultText() << "\n";
    return ExitCode::PlcFault;
  }
  if (!o.retainFile.empty()) {
    size_t restored = 0;
    std::string problem = plc::loadRetainFile(o.retainFile, *module, runtime.machine().memory(), restored);
    if (!problem.empty()) {
      std::cerr << "error: --retain-file: " << problem << "\n";
      return ExitCode::Usage;
    }
  }
  for (const auto& set : o.sets) {
    std::string problem = presetVariable(*module, set, runtime.machine().memory(), runtime.inputImage());
    if (!problem.empty()) {
      std::cerr << "error: --set " << problem << "\n";
      return ExitCode::Usage;
    }
  }

  std::ofstream traceFile;
  std::ostream* trace = &std::cout;
  if (!o.traceFile.empty()) {
    traceFile.open(o.traceFile);
    if (!traceFile) {
      std::cerr << "error: cannot write " << o.traceFile << "\n";
      return ExitCode::Usage;
    }
    trace = &traceFile;
  }
  if (!traceRefs.empty()) {
    *trace << "scan,time_ms";
    for (const auto& n : traceNames) *trace << ',' << n;
    *trace << '\n';
  }
  // Handlers first: a client may send SIGTERM as soon as the server announces itself.
  bool forever = o.cycles < 0 && speed > 0;
  if (forever) stopOnSignals();
  std::unique_ptr<proto::modbus::Server> modbus;
  if (!o.modbus.empty()) {
    auto server = startModbus(o, runtime);
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    modbus = std::move(*server);
    std::cerr << "modbus: serving on " << proto::modbus::formatEndpoint(modbus->endpoint()) << "\n";
  }
  std::unique_ptr<proto::ads::PlcServer> ads;
  if (o.ads.enabled()) {
    auto server = startAdsServer(o.ads, o.peers, *module);
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    ads = std::move(*server);
    ads->afterScan(runtime);
    announceAdsServer(o.ads, *ads);
  }
  std::unique_ptr<OpcuaPlcServer> opcua;
  if (o.opcua.enabled()) {
    auto server = startOpcuaServer(o.opcua, o.peers, module.get());
    if (!server) {
      std::cerr << "error: " << server.error() << "\n";
      return ExitCode::Usage;
    }
    opcua = std::move(*server);
    opcua->afterScan(runtime);
    announceOpcuaServer(*opcua);
  }
  const bool serving = modbus || ads || opcua;
  auto audit = serving ? makeWriteAudit(o.auditWrites, plc::auditedVariables(*module), std::cerr) : nullptr;
  int64_t cycles = o.cycles < 0 ? (forever ? INT64_MAX : 1) : o.cycles;
  if (paced) paced->resume();  // paced from the first scan: the set-up above is no scan's work
  ExitCode exitCode = ExitCode::Ok;
  for (int64_t k = 0; k < cycles && !gStopRequested; ++k) {
    int64_t now = runtime.nextTickNs();
    if (audit) audit->setVirtualTime(now);
    if (modbus && modbus->applyPendingWrites(modbusView(runtime), audit.get()) > 0) runtime.inputsTouched();
    if (ads) ads->beforeScan(runtime, audit.get());
    if (opcua) opcua->beforeScan(runtime, audit.get());
    bool ok = runtime.tick();
    if (modbus) modbus->publishSnapshot(modbusView(runtime));
    if (ads) ads->afterScan(runtime);
    if (opcua) opcua->afterScan(runtime);
    // An ADS client may STOP the PLC (WriteControl): time goes on, only a fault ends the run.
    if (!ok && runtime.state() != plc::PlcState::Fault) ok = true;
    if (!ok) {
      std::cerr << "runtime fault: " << runtime.faultText() << "\n";
      exitCode = ExitCode::PlcFault;
      break;
    }
    if (!traceRefs.empty()) writeTraceRow(*trace, *module, runtime.machine().memory(), static_cast<uint64_t>(k), now, traceRefs);
    if (o.traceSteps) {
      sfc::formatActiveSteps(steps, runtime.machine().memory(), activeSteps);
      std::cout << "scan " << k << " (" << now / 1'000'000 << " ms): " << (activeSteps.empty() ? "(none)" : activeSteps) << '\n';
    }
    if (ruleTracer) ruleTracer->print(static_cast<uint64_t>(k), runtime.machine().memory(), std::cout);
  }
  if (modbus) modbus->stop();
  if (ads) ads->stop();
  if (opcua) opcua->stop();
  if (!runtime.exit()) {
    std::cerr << "runtime fault in FB_exit: " << runtime.faultText() << "\n";
    exitCode = ExitCode::PlcFault;
  }
  backend.logRun(runtime.tierStats());
  if (paced) std::cerr << "timing: " << report::lateTicksText(paced->lateTicks(), runtime.ticks(), paced->maxLateNs()) << "\n";
  if (audit) std::cerr << auditSummary({audit.get()}) << "\n";
  if (!o.retainFile.empty() && exitCode == ExitCode::Ok) {
    std::string problem = plc::saveRetainFile(o.retainFile, *module, runtime.machine().memory());
    if (!problem.empty()) {
      std::cerr << "error: --retain-file: " << problem << "\n";
      exitCode = ExitCode::Usage;
    }
  }
  for (size_t i = 0; i < o.prints.size(); ++i)
    std::cout << o.prints[i] << " = " << bc::formatValue(*module, printRefs[i], runtime.machine().memory()) << "\n";
  // Also after a fault: what ran up to it is covered.
  if (o.coverage.enabled() &&
      !writeCoverage(o.coverage, bc::collectCoverage(*module, runtime.machine().memory()), "exec", std::cerr) &&
      exitCode == ExitCode::Ok)
    exitCode = ExitCode::Usage;
  if (o.stats) {
    for (size_t t = 0; t < module->tasks.size(); ++t) {
      const auto& s = runtime.stats(t);
      std::cerr << "task " << module->tasks[t].name << ": " << s.scans << " scans, exec min/avg/max "
                << s.minExecNs / 1000.0 << "/" << s.avgExecNs() / 1000.0 << "/" << s.maxExecNs / 1000.0 << " us\n";
    }
  }
  return exitCode;
}

}  // namespace

void addExecCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<ExecOptions>();
  CLI::App* cmd = app.add_subcommand("exec", "Run ST programs on the soft PLC for N scans in virtual time and print variables");
  cmd->add_option("files", o->files, kSourceFilesHelp)->required()->check(CLI::ExistingFile);
  cmd->add_option("--cycles", o->cycles, "number of scheduler ticks (scans of the fastest task) to run; default 1, or forever with --speed")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--cycle-time", o->cycleTime, "interval of the default task, e.g. 10ms (default 10ms)");
  cmd->add_option("--set", o->sets, "NAME=VALUE applied before the first scan (repeatable), e.g. MAIN.speed=5");
  cmd->add_option("--print", o->prints, "variable printed after the run as NAME = VALUE (repeatable)");
  cmd->add_option("--trace", o->traces, "comma-separated variables written as CSV after every tick");
  cmd->add_option("--trace-file", o->traceFile, "write the --trace CSV to this file instead of stdout");
  cmd->add_flag("--trace-steps", o->traceSteps, "print the active SFC steps after every tick: scan N (T ms): MAIN.Step1 ...");
  cmd->add_flag("--trace-rules", o->traceRules,
                "print the activity-diagram rules whose IF held, after every tick: scan N  Supply rule 3 fired: Valve := FALSE");
  cmd->add_option("--speed", o->speed, "pace to the wall clock (1 = real time); without --cycles runs until SIGINT/SIGTERM")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--budget", o->budget, "watchdog: max backward jumps + calls per task scan (default 50000000)");
  addBackendOption(*cmd, o->backend);
  addCoverageOptions(*cmd, o->coverage);
  cmd->add_flag("--stats", o->stats, "print per-task scan statistics to stderr");
  cmd->add_option("--modbus", o->modbus, "serve the process image over Modbus TCP on HOST:PORT (OpenPLC mapping, see docs/modbus.md); implies --speed 1");
  cmd->add_flag("--modbus-writable-inputs", o->modbusWritableInputs, "let --modbus clients write the inputs: holding register 8192+n is %IWn (and the %IX bits in it); off by default");
  addModbusServeOptions(cmd, o->modbusAllow, o->modbusReadOnly);
  addAdsServeOptions(cmd, o->ads);
  addOpcuaServeOptions(cmd, o->opcua);
  addPeerFlags(cmd, o->peers, true);
  addAuditOption(cmd, o->auditWrites);
  cmd->add_option("--retain-file", o->retainFile, "warm start: load the RETAIN/PERSISTENT variables from this file after the cold start (if it exists) and save them to it when the run ends without a fault");
  cmd->callback([o, setExit] { setExit(runExec(*o)); });
}

}  // namespace virtcom::cli
