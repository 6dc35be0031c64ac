// `virtcom test`: run scenario files (docs/scenarios.md) as a test suite: a PASS/FAIL line per
// case, JUnit XML, and the HTML report and VCD of every failing case.
#include <cctype>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>

#include "cli/commands.hpp"
#include "bytecode/coverage.hpp"
#include "cli/common.hpp"
#include "cli/ads_client.hpp"
#include "cli/opcua_client.hpp"
#include "cli/coverage_options.hpp"
#include "cli/modbus_options.hpp"
#include "cli/plc_backend.hpp"
#include "report/html_report.hpp"
#include "report/kpis.hpp"
#include "report/waveform.hpp"
#include "scenario/junit.hpp"
#include "scenario/suite.hpp"

namespace virtcom::cli {

namespace {

struct TestOptions {
  std::vector<std::string> paths;
  std::string junit;
  std::string filter;
  std::string reportDir;
  unsigned jobs = 0;  // 0: one per hardware thread
  std::string backend = "auto";
  CoverageOptions coverage;
};

// A case's name as a file name: letters, digits, '-', '_' and '.' kept, the rest '_'.
std::string fileStem(const std::string& name) {
  std::string stem = name;
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return stem;
}

// The failing case's HTML report and VCD in `dir`, named after the case; false if not written.
bool writeCaseReports(const std::string& dir, const scenario::CaseResult& r) {
  const Trace& trace = r.cell->trace;
  report::HtmlOptions html;
  html.title = r.spec.name;
  html.subtitle = r.spec.file + ": " + std::string(scenario::verdictName(r.verdict));
  const std::string stem = (std::filesystem::path(dir) / fileStem(r.spec.name)).string();
  bool ok = writeFile(stem + ".html", report::htmlReport(trace, report::computeKpis(trace), html));
  return writeFile(stem + ".vcd", report::vcdReport(trace)) && ok;
}

// The bridge to a case's external PLC (`plc: ads:`, `modbus:` or `opcua:`), as `virtcom run` starts
// it, added to the case's options; the case runs in real time, as the external PLC does.
std::shared_ptr<void> startExternalPlcLink(cell::Cell& cell, const SourceManager& sources, sim::SimOptions& sim, std::string& error) {
  sim.speed = 1;
  if (cell.plcModbus) {
    std::shared_ptr<proto::modbus::ClientBridge> bridge = startClientBridge(*cell.plcModbus, "is the controller");
    sim.bridges.push_back(bridge.get());
    return bridge;
  }
  if (cell.plcOpcua) {
    std::shared_ptr<proto::opcua::ClientBridge> bridge = startOpcuaBridge(cell, sources, "is the controller");
    if (!bridge) {
      error = "the external PLC at " + cell.plcOpcua->url + " could not be used (see the errors above)";
      return nullptr;
    }
    sim.bridges.push_back(bridge.get());
    return bridge;
  }
  std::shared_ptr<proto::ads::ClientBridge> bridge = startAdsBridge(cell, sources, "is the controller");
  if (!bridge) {
    error = "the external PLC at " + cell.plcAds->address + " could not be used (see the errors above)";
    return nullptr;
  }
  sim.bridges.push_back(bridge.get());
  return bridge;
}

void printResult(const scenario::CaseResult& r) {
  std::cout << scenario::verdictName(r.verdict) << "  " << r.spec.name << "  (" << r.spec.file;
  if (r.verdict != scenario::Verdict::Error)
    std::cout << ", " << r.runEnd.substr(0, r.runEnd.find(':')) << " at " << static_cast<double>(r.virtualNs) * 1e-9 << " s";
  std::cout << ")\n";
  for (const std::string& m : r.messages) {
    std::string text = m;
    while (!text.empty() && text.back() == '\n') text.pop_back();
    for (size_t at = 0; (at = text.find('\n', at)) != std::string::npos; at += 5) text.replace(at, 1, "\n    ");
    std::cout << "    " << text << "\n";
  }
}

ExitCode runTests(const TestOptions& o) {
  std::string error;
  const std::vector<scenario::CaseSpec> cases = scenario::collectCases(o.paths, o.filter, error);
  if (!error.empty()) {
    std::cerr << "error: " << error << "\n";
    return ExitCode::Usage;
  }
  if (cases.empty()) {
    std::cerr << "error: no scenario found" << (o.filter.empty() ? "" : " matching --filter '" + o.filter + "'") << " (scenario files end in .yaml)\n";
    return ExitCode::Usage;
  }
  if (!o.reportDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.reportDir, ec);
    if (ec) {
      std::cerr << "error: --report-dir: cannot create " << o.reportDir << ": " << ec.message() << "\n";
      return ExitCode::Usage;
    }
  }
  scenario::CaseOptions options;
  options.keepFailedCell = !o.reportDir.empty();
  // PLC code coverage: every case's program compiled with probes; its counts, read from the PLC
  // memory when its run ends (on the worker threads), added to the suite's. Merging adds counts,
  // so the result does not depend on the order the cases end in (nor on --jobs).
  CoverageData coverage;
  std::mutex coverageMutex;
  options.plc = withModuleCache(o.coverage.compileOptions());
  if (o.coverage.enabled()) {
    options.hooks.afterRun = [&](sim::Simulation& simulation) {
      if (!simulation.hasPlc()) return;
      CoverageData counted = bc::collectCoverage(simulation.plc().module(), simulation.plc().machine().memory());
      std::lock_guard lock(coverageMutex);
      coverage.merge(counted);
    };
  }
  // Each case's PLC on the chosen backend (machine code from the AOT cache after the first case
  // of a program); the backends give the same results, so the verdicts do not depend on it.
  options.hooks.beforeRun = [&o](cell::Cell& cell, const SourceManager& sources, sim::SimOptions& sim,
                                 std::string& error) -> std::shared_ptr<void> {
    if (!cell.module) return startExternalPlcLink(cell, sources, sim, error);
    auto backend = std::make_shared<PlcBackend>(o.backend, *cell.module);
    sim.compiled = backend->compiled();
    sim.tierUp = backend->tierUp();
    return backend;
  };
  const unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  std::vector<scenario::CaseResult> results;
  bool reportsOk = true;
  scenario::runCases(cases, jobs, options, [&](scenario::CaseResult& r) {
    printResult(r);
    if (r.cell) {
      reportsOk = writeCaseReports(o.reportDir, r) && reportsOk;
      r.cell.reset();
    }
    results.push_back(std::move(r));
  });
  size_t failed = 0, expected = 0;
  for (const auto& r : results) {
    failed += scenario::verdictFails(r.verdict);
    expected += r.verdict == scenario::Verdict::ExpectedFail;
  }
  std::cout << results.size() << " scenario(s): " << results.size() - failed - expected << " passed, " << failed << " failed";
  if (expected) std::cout << ", " << expected << " failed as expected (xfail)";
  std::cout << "\n";
  if (!o.junit.empty() && !writeFile(o.junit, scenario::junitXml(results))) return ExitCode::Usage;
  if (o.coverage.enabled() && !writeCoverage(o.coverage, coverage, "scenarios", std::cerr)) return ExitCode::Usage;
  if (!reportsOk) return ExitCode::Usage;
  return failed ? ExitCode::TestsFailed : ExitCode::Ok;
}

}  // namespace

void addTestCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<TestOptions>();
  CLI::App* cmd = app.add_subcommand("test", "Run scenario files (docs/scenarios.md) as tests: stimuli, faults and assertions on simulated cells");
  cmd->add_option("paths", o->paths, "scenario files, or directories searched for *.yaml scenarios")->required();
  cmd->add_option("--junit", o->junit, "write the results as JUnit XML to this file (for CI)");
  cmd->add_option("--jobs,-j", o->jobs, "run this many scenarios at once (default: one per core); results do not depend on it")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--filter", o->filter, "run only the cases whose name or file matches this glob (* and ?), e.g. 'cycle*'");
  cmd->add_option("--report-dir", o->reportDir, "write the HTML report and the VCD of every failing case into this directory");
  addBackendOption(*cmd, o->backend);
  addCoverageOptions(*cmd, o->coverage);
  cmd->callback([o, setExit] { setExit(runTests(*o)); });
}

}  // namespace virtcom::cli
