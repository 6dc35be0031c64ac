// One scenario case, from its file to its verdict.
#include "scenario/runner.hpp"

#include <filesystem>

#include "core/cell_diagnostic_codes.hpp"
#include "core/clock.hpp"
#include "scenario/bind.hpp"
#include "scenario/checker.hpp"
#include "scenario/scenario_file.hpp"
#include "scenario/stimuli.hpp"

namespace virtcom::scenario {

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "PASS";
    case Verdict::Fail: return "FAIL";
    case Verdict::Error: return "ERROR";
    case Verdict::ExpectedFail: return "XFAIL";
    case Verdict::UnexpectedPass: return "XPASS";
  }
  return "?";
}

bool verdictFails(Verdict v) { return v == Verdict::Fail || v == Verdict::Error || v == Verdict::UnexpectedPass; }

namespace {

// The cell of `program:`, a PLC program alone: `program: main.st`, a list of sources, or
// `{sources: [...], cycle_time: 10 ms}`, read as a cell file's `plc:` section (sources relative to
// the scenario) into a cell with an empty device list. Null, with the mistakes in `diags`, on any error.
std::unique_ptr<cell::Cell> loadProgramCell(const std::string& scenarioFile, const ConfigNode& program,
                                            const st::CompileOptions& plcOptions, SourceManager& sources, Diagnostics& diags) {
  ConfigNode plc = ConfigNode::makeMap(program.loc());
  if (program.kind() == ConfigNode::Kind::Map) {
    ConfigReader r(program, diags, "'program'");
    if (const ConfigNode* srcs = r.child("sources")) plc.add("sources", program.keyLoc("sources"), *srcs);
    else r.error(program.loc(), "'program' names its 'sources', e.g. {sources: [main.st], cycle_time: 10 ms}");
    if (const ConfigNode* cycle = r.child("cycle_time")) plc.add("cycle_time", program.keyLoc("cycle_time"), *cycle);
    r.rejectUnknownKeys();
  } else {
    ConfigNode list = ConfigNode::makeList(program.loc());
    if (program.kind() == ConfigNode::Kind::List)
      for (const ConfigNode& item : program.items()) list.push(item);
    else
      list.push(program);
    plc.add("sources", program.loc(), std::move(list));
  }
  if (diags.hasErrors()) return nullptr;
  ConfigNode root = ConfigNode::makeMap(program.loc());
  root.add("plc", program.loc(), std::move(plc));
  root.add("devices", program.loc(), ConfigNode::makeList(program.loc()));
  return cell::loadCellTree(scenarioFile, root, sources, diags, plcOptions);
}

// The scenario's cell and plan, or null with the diagnostics in `diags`.
std::unique_ptr<cell::Cell> loadScenario(const CaseSpec& spec, const st::CompileOptions& plcOptions, SourceManager& sources,
                                         Diagnostics& diags, Plan& plan) {
  ScenarioFile file;
  if (!readScenarioFile(spec.file, sources, diags, file)) return nullptr;
  ConfigNode root = spec.row < file.rows.size() ? substituteParameters(file.root, file.rows[spec.row], diags) : file.root;
  if (diags.hasErrors()) return nullptr;
  ConfigReader top(root, diags, "the scenario");
  top.optString("name", "");
  top.optString("description", "");
  const ConfigNode* program = top.child("program");
  if (program && root.has("cell")) {
    diags.error(celldiag::C060, root.keyLoc("program"),
                "a scenario runs either a cell ('cell:') or a PLC program alone ('program:'), not both");
    return nullptr;
  }
  if (program) {
    auto cell = loadProgramCell(spec.file, *program, plcOptions, sources, diags);
    if (!cell) return nullptr;
    plan = bindScenario(top, *cell, Controlled::ProgramAlone);
    return diags.hasErrors() ? nullptr : std::move(cell);
  }
  if (!root.has("cell")) {
    diags.error(celldiag::C060, root.loc(),
                "a scenario names the cell it runs ('cell: ../cell.yaml') or a PLC program alone ('program: main.st')");
    return nullptr;
  }
  const std::string cellName = top.requireString("cell");
  if (cellName.empty()) return nullptr;
  const std::filesystem::path cellPath = (std::filesystem::path(spec.file).parent_path() / cellName).lexically_normal();
  auto cell = cell::loadCell(cellPath.string(), sources, diags, plcOptions);
  if (!cell) return nullptr;
  if (!cell->module && !cell->externalPlc()) {
    diags.error(celldiag::C060, root.find("cell")->loc(),
                "the cell '" + cellName + "' has no controller: scenarios drive its soft PLC ('plc: sources') or an external one ('plc: ads:', "
                "'plc: modbus:', 'plc: opcua:')");
    return nullptr;
  }
  plan = bindScenario(top, *cell, Controlled::Cell);
  if (diags.hasErrors()) return nullptr;
  return cell;
}

std::string renderFailure(const Failure& f, const Assertion& a, const SourceManager& sources) {
  return sources.path(f.loc.fileId) + ":" + std::to_string(f.loc.line) + ": " + a.what + ": at " + formatSeconds(f.timeNs) + ": " +
         f.message;
}

}  // namespace

CaseResult runCase(const CaseSpec& spec, const CaseOptions& options) {
  const int64_t startedNs = monotonicNowNs();
  CaseResult result;
  result.spec = spec;
  SourceManager sources;
  Diagnostics diags;
  Plan plan;
  auto cell = loadScenario(spec, options.plc, sources, diags, plan);
  if (!cell) {
    diags.sortByLocation();
    result.messages.push_back(diags.render(sources));
    result.wallNs = monotonicNowNs() - startedNs;
    return result;
  }
  Stimuli stimuli(plan, *cell);
  Checker checker(plan, *cell);
  sim::SimOptions o;
  o.preset = [&stimuli](plc::Runtime& plc) { stimuli.preset(plc); };
  if (!plan.steps.empty()) o.beforeScan = [&stimuli](plc::Runtime& plc) { stimuli.beforeScan(plc); };
  o.traceSinks.push_back(&checker);
  // A failed case's report shows every signal; a passing case keeps none (bounded memory).
  o.keepAllChanges = options.keepFailedCell;
  std::string hookError;
  std::shared_ptr<void> keptForTheRun = options.hooks.beforeRun ? options.hooks.beforeRun(*cell, sources, o, hookError) : nullptr;
  if (!hookError.empty()) {
    result.messages.push_back(hookError);
    result.wallNs = monotonicNowNs() - startedNs;
    return result;
  }
  // The external PLC's link, cut in the scenario's windows (its bridges come from the hook).
  std::vector<std::unique_ptr<LinkLossBridge>> cutLinks;
  if (!plan.linkLosses.empty()) {
    const bool faultOnLoss = cell->plcAds     ? cell->plcAds->faultOnLoss
                             : cell->plcOpcua ? cell->plcOpcua->faultOnLoss
                                              : cell->plcModbus->faultOnLoss;
    for (BusBridge*& b : o.bridges) b = cutLinks.emplace_back(std::make_unique<LinkLossBridge>(*b, plan.linkLosses, faultOnLoss)).get();
  }
  {
    sim::Simulation simulation(*cell, o);
    if (simulation.hasPlc()) checker.attach(&simulation.plc());
    simulation.run();
    if (options.hooks.afterRun) options.hooks.afterRun(simulation);
  }
  const Trace& trace = cell->trace;
  result.virtualNs = trace.endNs;
  result.runEnd = std::string(runEndName(trace.end)) + ": " + trace.endMessage;
  for (const Failure& f : checker.failures()) result.messages.push_back(renderFailure(f, plan.assertions[f.assertion], sources));
  const bool failed = !result.messages.empty();
  if (plan.xfail.empty()) result.verdict = failed ? Verdict::Fail : Verdict::Pass;
  else result.verdict = failed ? Verdict::ExpectedFail : Verdict::UnexpectedPass;
  if (result.verdict == Verdict::UnexpectedPass) result.messages.push_back("expected to fail (xfail: " + plan.xfail + "), but every assertion held");
  if (options.keepFailedCell && verdictFails(result.verdict)) result.cell = std::move(cell);
  result.wallNs = monotonicNowNs() - startedNs;
  return result;
}

}  // namespace virtcom::scenario
