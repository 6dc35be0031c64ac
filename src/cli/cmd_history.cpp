// `virtcom history FILE.sqlite`: the runs a history database holds (recorded by `run` or
// `serve` with --history), and one run, or a time range of it, exported through the same
// writers as `virtcom run` (CSV, VCD, the JSON and HTML reports), or browsed in the web HMI
// (--http: the page's Gantt, trends and layout over the recorded runs). docs/history.md.
#include <chrono>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/hmi_options.hpp"
#include "core/write_audit.hpp"
#include "history/query.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/waveform.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

namespace {

struct HistoryOptions {
  std::string file;
  int64_t run = 0;  // 0: the newest
  std::string from, to;
  std::string csv, vcd, html, json;
  std::vector<std::string> signals;
  bool writes = false;   // --writes: list the run's audited writes from outside
  HmiServeOptions http;  // --http: browse in the web HMI
  PeerFlags peers;       // --allow-any-peer
  std::string cell;      // --cell: the cell file the page draws (default: the run's)
  bool exports() const { return !csv.empty() || !vcd.empty() || !html.empty() || !json.empty(); }
};

std::string utcText(int64_t utcNs) {
  std::time_t seconds = static_cast<std::time_t>(utcNs / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  std::ostringstream out;
  out << std::put_time(&tm, "%Y-%m-%d %H:%M:%S");
  return out.str();
}

std::string endText(const history::RunSummary& r) {
  if (!r.writerError.empty()) return "recording failed: " + r.writerError;
  return r.ended ? r.endReason : "not ended: running or killed";
}

void printRuns(const std::vector<history::RunSummary>& runs) {
  std::cout << std::left << std::setw(5) << "run" << std::setw(22) << "cell" << std::setw(21) << "started (UTC)" << std::right
            << std::setw(14) << "virtual s" << "  " << std::left << std::setw(30) << "end" << std::right << std::setw(10) << "changes"
            << std::setw(12) << "activities" << std::setw(8) << "drops" << std::setw(8) << "writes" << "\n";
  for (const auto& r : runs)
    std::cout << std::left << std::setw(5) << r.id << std::setw(22) << r.cellName << std::setw(21) << utcText(r.wallStartNs) << std::right
              << std::setw(14) << std::fixed << std::setprecision(3) << static_cast<double>(r.endNs) * 1e-9 << "  " << std::left
              << std::setw(30) << endText(r) << std::right << std::setw(10) << r.changes << std::setw(12) << r.activities << std::setw(8)
              << r.drops << std::setw(8) << r.writes << "\n";
}

// A monitored run's shifts against its plan (virtcom monitor with a `plan:`), if it has any.
void printProduction(const std::vector<history::ProductionRow>& rows) {
  if (rows.empty()) return;
  std::cout << "\n" << std::left << std::setw(12) << "day" << std::setw(14) << "shift" << std::right << std::setw(8) << "plan"
            << std::setw(10) << "plan now" << std::setw(8) << "actual" << "\n";
  for (const auto& r : rows)
    std::cout << std::left << std::setw(12) << r.day << std::setw(14) << r.shift << std::right << std::setw(8) << r.plan << std::setw(10)
              << std::fixed << std::setprecision(1) << r.planNow << std::setw(8) << r.actual << "\n";
}

// --from/--to as a range; nullopt after an error message.
std::optional<history::TimeRange> timeRange(const HistoryOptions& o) {
  history::TimeRange range;
  for (auto [text, option, target] : {std::tuple{&o.from, "--from", &range.fromNs}, std::tuple{&o.to, "--to", &range.toNs}}) {
    if (text->empty()) continue;
    auto ns = parseDurationNs(*text);
    if (!ns || *ns < 0) {
      std::cerr << "error: " << option << ": '" << *text << "' is not a duration (e.g. 10s, 1500ms, T#1m30s)\n";
      return std::nullopt;
    }
    *target = *ns;
  }
  if (range.fromNs > range.toNs) {
    std::cerr << "error: --from " << o.from << " is after --to " << o.to << "\n";
    return std::nullopt;
  }
  return range;
}

bool exportRun(const HistoryOptions& o, history::HistoryReader& reader, const history::RunSummary& run, history::TimeRange range) {
  size_t skipped = 0;
  const Trace trace = reader.trace(run.id, range, &skipped);
  if (skipped > 0)
    std::cerr << "warning: " << o.file << ": " << skipped << " row(s) of run " << run.id
              << " name a signal, device or label the run does not have; left out\n";
  bool ok = true;
  if (!o.csv.empty()) ok = writeFile(o.csv, report::csvChanges(trace)) && ok;
  if (!o.vcd.empty()) ok = writeFile(o.vcd, report::vcdReport(trace)) && ok;
  if (o.html.empty() && o.json.empty()) return ok;
  const report::Kpis kpis = report::computeKpis(trace);
  if (!o.json.empty()) ok = writeFile(o.json, report::jsonReport(trace, kpis)) && ok;
  if (!o.html.empty()) {
    report::HtmlOptions html;
    html.title = run.cellName;
    html.signals = o.signals.empty() ? run.timeline : o.signals;
    ok = writeFile(o.html, report::htmlReport(trace, kpis, html)) && ok;
  }
  return ok;
}

// `--http`: the page served over the history, read-only, until Ctrl-C. The layout is drawn from
// the cell file of the run shown first (as recorded, or --cell); the Gantt chart and the trends
// of any run come from the database.
ExitCode browseHistory(const HistoryOptions& o, history::HistoryReader& reader) {
  HmiServeOptions http = o.http;
  http.readOnly = true;  // nothing to write: no token is made up
  auto binding = checkHmiOptions(http, o.peers, "--http");
  if (!binding) {
    std::cerr << "error: " << binding.error() << "\n";
    return ExitCode::Usage;
  }
  const int64_t id = o.run > 0 ? o.run : reader.lastRunId();
  auto run = reader.run(id);
  if (!run && o.cell.empty()) {
    std::cerr << "error: " << o.file << ": " << (id == 0 ? "no run recorded yet" : "no run " + std::to_string(id))
              << ": the page draws the layout of a run's cell file (or give --cell CELL.yaml)\n";
    return ExitCode::HistoryError;
  }
  const std::string cellFile = o.cell.empty() ? run->cellFile : o.cell;
  SourceManager sources;
  auto cell = loadCellFile(cellFile, sources);
  if (!cell) {
    std::cerr << "error: --http: the page draws the layout of " << cellFile
              << ", which does not load (see above): give the cell file with --cell CELL.yaml\n";
    return ExitCode::Usage;
  }
  auto api = hmi::HistoryApi::open(o.file);
  if (!api) {
    std::cerr << "error: " << api.error() << "\n";
    return ExitCode::HistoryError;
  }
  // Never run: it prepares the devices (trace indexes, labels) the page's model describes.
  sim::Simulation prepared(*cell, {});
  hmi::LiveState live(*cell, &gStopRequested, true);  // never published: the page shows only the history
  hmi::Api page(*cell, live, prepared.hasPlc() ? prepared.plc().baseTickNs() : cell->run.plcCycleNs, binding->access);
  page.attachHistory(**api, true);
  stopOnSignals();
  auto server = hmi::HttpServer::start(page, binding->at, binding->peers);
  if (!server) {
    std::cerr << "error: --http: " << server.error() << "\n";
    return ExitCode::Usage;
  }
  std::cerr << "hmi: serving http://" << formatEndpoint((*server)->bound()) << "/ (history of " << o.file
            << ", read-only) until Ctrl-C\n";
  while (!gStopRequested.load()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  (*server)->stop();
  return ExitCode::Ok;
}

ExitCode showHistory(const HistoryOptions& o) {
  auto range = timeRange(o);
  if (!range) return ExitCode::Usage;
  if (o.http.enabled() && (o.exports() || o.writes || !range->whole() || !o.signals.empty())) {
    std::cerr << "error: --http browses the history in the web HMI: it takes no --csv, --vcd, --report, --json, --writes, --from, --to or --signal\n";
    return ExitCode::Usage;
  }
  if (!o.http.enabled() && (!o.cell.empty() || !o.http.allow.empty() || o.peers.anyPeer)) {
    std::cerr << "error: --cell, --http-allow and --allow-any-peer go with --http\n";
    return ExitCode::Usage;
  }
  if (!o.exports() && (!range->whole() || !o.signals.empty()) && !(o.writes && o.signals.empty())) {
    std::cerr << "error: --from, --to and --signal select what is exported: add --csv, --vcd, --report or --json (--from and --to also "
                 "go with --writes)\n";
    return ExitCode::Usage;
  }
  auto reader = history::HistoryReader::open(o.file);
  if (!reader) {
    std::cerr << "error: " << reader.error() << "\n";
    return ExitCode::HistoryError;
  }
  if (o.http.enabled()) return browseHistory(o, *reader);
  const int64_t id = o.run > 0 ? o.run : reader->lastRunId();
  if (o.run == 0 && !o.exports() && !o.writes) {
    printRuns(reader->runs());
    return ExitCode::Ok;
  }
  auto run = reader->run(id);
  if (!run) {
    std::cerr << "error: " << o.file << ": " << (id == 0 ? "no run recorded yet" : "no run " + std::to_string(id))
              << " (virtcom history " << o.file << " lists the runs)\n";
    return ExitCode::HistoryError;
  }
  if (o.writes) {
    // As `--audit-writes each` logged them while the run went on (docs/security.md).
    for (const WriteRecord& w : reader->writes(id, *range)) std::cout << formatWriteRecordWithTimes(w) << "\n";
    if (!o.exports()) return ExitCode::Ok;
  }
  if (!o.exports()) {
    printRuns({*run});
    printProduction(reader->production(id));
    return ExitCode::Ok;
  }
  return exportRun(o, *reader, *run, *range) ? ExitCode::Ok : ExitCode::Usage;
}

}  // namespace

void addHistoryCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<HistoryOptions>();
  CLI::App* cmd = app.add_subcommand(
      "history", "List the runs a history database holds (recorded with run/serve --history), export one run or a time range of it "
                 "as CSV, VCD or a report, or browse them in the web HMI (--http)");
  cmd->add_option("file", o->file, "the history database (SQLite), e.g. cell.sqlite")->required();
  cmd->add_option("--run", o->run, "the run to show or export (an id from the list; default: the newest)")->check(CLI::PositiveNumber);
  cmd->add_option("--from", o->from, "export from this virtual time on, e.g. 10s, 1500ms (default: the start); times become relative to it");
  cmd->add_option("--to", o->to, "export up to this virtual time, e.g. 20s (default: the end)");
  cmd->add_option("--csv", o->csv, "write the signal changes as CSV (as run --csv) to this file");
  cmd->add_option("--vcd", o->vcd, "write the signal changes as VCD (as run --vcd) to this file");
  cmd->add_option("--report", o->html, "write the HTML report (as run --report) to this file");
  cmd->add_option("--json", o->json, "write the JSON report (as run --json) to this file");
  cmd->add_flag("--writes", o->writes,
                "list the run's audited writes from outside (ADS, Modbus, OPC UA, HMI), one line each as --audit-writes each "
                "logged them: virtual and UTC time, protocol, peer, variable, old -> new value (with --from/--to: in that range)");
  cmd->add_option("--signal", o->signals, "signal shown in the report's timeline (repeatable); default: those of the recorded run");
  addHttpOptions(cmd, o->http, "--http",
                 "browse the runs in the web HMI instead (their Gantt chart, trends and layout over time, read-only)");
  addPeerFlags(cmd, o->peers, false);
  cmd->add_option("--cell", o->cell, "with --http: the cell file whose layout the page draws (default: the one the run recorded)");
  cmd->callback([o, setExit] { setExit(showHistory(*o)); });
}

}  // namespace virtcom::cli
