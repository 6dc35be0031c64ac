// `virtcom optimise MODEL.yaml`: search the orders of a process model for the shortest cycle, the
// least energy or both (docs/optimise.md); every candidate run by the cell's real PLC program.
// Under mpirun the evaluations are spread over the ranks (docs/scaling.md); rank 0 reports.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "core/clock.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/ranks.hpp"
#include "optimize/search.hpp"
#include "report/html_report.hpp"
#include "report/kpis.hpp"

namespace virtcom::cli {

namespace {

struct OptimiseOptions {
  std::string model;
  std::string objective;  // empty: the model's
  uint64_t budgetEvals = 2000;
  std::string budgetTime;
  uint64_t seed = 1;
  size_t batch = 16;
  unsigned jobs = 0;      // 0: every core (one per rank under mpirun)
  std::string method = "auto";
  std::string out;
  bool quiet = false;
};

std::string fixed(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string row(const std::string& name, const optimize::Evaluation& e, const std::string& note) {
  if (!e.feasible) return "| " + name + " | - | - | infeasible: " + e.reason + " |\n";
  return "| " + name + " | " + fixed(static_cast<double>(e.cycleNs) * 1e-9, 3) + " | " + fixed(e.energyJ, 1) + " | " + note + " |\n";
}

// The comparison of the user's sequences with the best candidates found (Markdown).
std::string comparisonTable(const optimize::ProcessModel& m, const std::vector<optimize::Evaluation>& user, const optimize::SearchResult& r,
                            const std::string& outDir) {
  std::string s = "| sequence | cycle s | energy J | result |\n| --- | --- | --- | --- |\n";
  for (size_t i = 0; i < user.size(); ++i) s += row("yours: " + m.sequences[i].name, user[i], "feasible");
  for (size_t i = 0; i < r.best.size(); ++i) {
    const std::string name = "best-" + std::to_string(i + 1);
    s += row("found: " + name, r.best[i].eval, outDir.empty() ? "feasible" : "feasible: " + name + ".st, " + name + ".html");
  }
  return s;
}

// best-N.st (the job list to paste into the PLC program) and best-N.html (its run's report).
bool writeBest(const OptimiseOptions& o, const optimize::Evaluator& evaluator, const optimize::SearchResult& r, const std::string& table) {
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  const optimize::ProcessModel& m = evaluator.model();
  bool ok = true;
  for (size_t i = 0; i < r.best.size(); ++i) {
    const std::string base = (std::filesystem::path(o.out) / ("best-" + std::to_string(i + 1))).string();
    const optimize::Evaluation& e = r.best[i].eval;
    std::string st = "(* virtcom optimise " + m.file.filename().string() + " (seed " + std::to_string(o.seed) + "): cycle " +
                     fixed(static_cast<double>(e.cycleNs) * 1e-9, 3) + " s, energy " + fixed(e.energyJ, 1) + " J.\n   The job list as an initialiser of " +
                     m.jobList.variable + " (docs/optimise.md \"Job lists\"). *)\n";
    st += optimize::jobListSt(m, r.best[i].list, evaluator.arrayName(), evaluator.arrayType());
    ok = writeFile(base + ".st", st) && ok;
    optimize::Evaluation again;
    auto cell = evaluator.run(r.best[i].list, again);
    if (!cell) continue;
    report::HtmlOptions html;
    html.title = cell->name + " — optimised sequence best-" + std::to_string(i + 1);
    html.signals = cell->run.recordVars;
    ok = writeFile(base + ".html", report::htmlReport(cell->trace, report::computeKpis(cell->trace), html)) && ok;
  }
  return writeFile((std::filesystem::path(o.out) / "comparison.txt").string(), table) && ok;
}

ExitCode optimise(const OptimiseOptions& o) {
  const optimize::Ranks ranks;
  if (!ranks.problem().empty()) {
    std::cerr << "error: " << ranks.problem() << "\n";
    return ExitCode::Usage;
  }
  SourceManager sources;
  Diagnostics diags;
  auto model = optimize::readProcessModel(o.model, sources, diags);
  std::unique_ptr<optimize::Evaluator> evaluator;
  if (model) evaluator = optimize::Evaluator::create(*model, sources, diags);
  if (ranks.leader()) std::cerr << diags.render(sources);
  if (!evaluator) return ExitCode::InputError;
  optimize::SearchOptions so;
  so.objective = model->objective;
  if (o.objective == "time") so.objective = optimize::Objective::Time;
  else if (o.objective == "energy") so.objective = optimize::Objective::Energy;
  else if (o.objective == "both") so.objective = optimize::Objective::Both;
  so.budgetEvals = o.budgetEvals;
  so.seed = o.seed;
  so.batch = o.batch;
  so.method = o.method == "exhaustive" ? optimize::Method::Exhaustive : o.method == "anneal" ? optimize::Method::Anneal : optimize::Method::Auto;
  const unsigned threads = o.jobs ? o.jobs : ranks.size() > 1 ? 1u : std::max(1u, std::thread::hardware_concurrency());
  const int64_t startNs = monotonicNowNs();
  int64_t deadlineNs = 0;
  if (!o.budgetTime.empty()) {
    auto ns = parseDurationNs(o.budgetTime);
    if (!ns || *ns <= 0) {
      std::cerr << "error: --budget-time: '" << o.budgetTime << "' is not a duration (e.g. 90s, 5m)\n";
      return ExitCode::Usage;
    }
    deadlineNs = startNs + *ns;
  }
  stopOnSignals();
  // The leader's clock decides for every rank, so all of them search alike.
  so.stop = [&] { return ranks.leaderDecides(gStopRequested.load() || (deadlineNs && monotonicNowNs() >= deadlineNs)); };
  int64_t lastPrintNs = 0;
  so.progress = [&](const optimize::Progress& p) {
    const int64_t now = monotonicNowNs();
    if (o.quiet || !ranks.leader() || now - lastPrintNs < 1'000'000'000) return;
    lastPrintNs = now;
    const double rate = static_cast<double>(p.evaluations) / std::max(1e-9, static_cast<double>(now - startNs) * 1e-9);
    std::cerr << "optimise: " << p.evaluations << " evaluations, " << fixed(rate, 1) << "/s, " << p.infeasible << " infeasible, best "
              << (p.best ? fixed(static_cast<double>(p.best->eval.cycleNs) * 1e-9, 3) + " s, " + fixed(p.best->eval.energyJ, 1) + " J" : "none");
    if (so.objective == optimize::Objective::Both) std::cerr << ", front " << p.frontSize;
    std::cerr << "\n";
  };
  optimize::BatchEvaluator batch = [&](const std::vector<optimize::JobList>& lists) {
    return ranks.evaluateAll(lists.size(), threads, [&](size_t i) { return evaluator->evaluate(lists[i]); });
  };
  std::vector<optimize::JobList> userLists;
  for (const auto& s : model->sequences) userLists.push_back(optimize::buildJobList(*model, s.candidate));
  const std::vector<optimize::Evaluation> user = batch(userLists);
  optimize::SearchResult r = optimize::search(*model, batch, so);
  const double wallS = static_cast<double>(monotonicNowNs() - startNs) * 1e-9;
  if (!ranks.leader()) return r.best.empty() ? ExitCode::RunStopped : ExitCode::Ok;
  std::cout << "method: " << (r.method == optimize::Method::Exhaustive ? "exhaustive" : "simulated annealing") << " (" << r.why << ")\n"
            << "objective: " << optimize::objectiveName(so.objective) << ", seed " << o.seed << ", " << threads << " thread(s)"
            << (ranks.size() > 1 ? " on each of " + std::to_string(ranks.size()) + " MPI ranks" : std::string()) << "\n"
            << "evaluations: " << r.evaluations << " (" << r.infeasible << " infeasible, " << r.repeats << " repeats not simulated) in "
            << fixed(wallS, 1) << " s: " << fixed(static_cast<double>(r.evaluations) / std::max(wallS, 1e-9) * 3600, 0) << " per hour\n"
            << (r.complete ? "every distinct candidate was evaluated: the best is optimal for this model\n" : "");
  const std::string table = comparisonTable(*model, user, r, o.out);
  std::cout << "\n" << table;
  if (!r.rejected.empty()) {
    std::cout << "\nrejected (the first candidate of each kind):\n";
    for (const auto& s : r.rejected) std::cout << "  " << s.eval.reason << "\n";
  }
  if (!o.out.empty() && !writeBest(o, *evaluator, r, table)) return ExitCode::Usage;
  if (r.best.empty()) {
    std::cerr << "optimise: no feasible candidate found within the budget\n";
    return ExitCode::RunStopped;
  }
  return ExitCode::Ok;
}

}  // namespace

void addOptimiseCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<OptimiseOptions>();
  CLI::App* cmd = app.add_subcommand("optimise", "Search the operation orders of a process model (docs/optimise.md) for the shortest cycle, "
                                                 "the least energy or both, each candidate simulated with the cell's PLC program");
  cmd->alias("optimize");
  cmd->add_option("model", o->model, "the process model (YAML): operations, precedence, resources, the PLC's job list")->required()->check(CLI::ExistingFile);
  cmd->add_option("--objective", o->objective, "time (cycle time), energy (all devices) or both (Pareto front); default: the model's 'objective'")
      ->check(CLI::IsMember({"time", "energy", "both"}));
  cmd->add_option("--budget-evals", o->budgetEvals, "simulations at most (default 2000); with a seed, the result depends only on these two")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--budget-time", o->budgetTime, "stop after this wall time, e.g. 90s, 5m (results then depend on the machine's speed)");
  cmd->add_option("--seed", o->seed, "seed of the search's random choices (default 1)");
  cmd->add_option("--batch", o->batch, "candidates simulated together (default 16): at most this many threads and MPI ranks are busy at once; "
                                       "the search's path depends on it, so compare runs with the same --batch")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--jobs", o->jobs, "simulations in parallel (default: every core; under mpirun one per rank); never changes the result")->check(CLI::PositiveNumber);
  cmd->add_option("--method", o->method, "auto (default: exhaustive if the distinct candidates fit the budget, else anneal), exhaustive, anneal")
      ->check(CLI::IsMember({"auto", "exhaustive", "anneal"}));
  cmd->add_option("--out", o->out, "write best-N.st (the job list to paste), best-N.html (its report) and comparison.txt into this folder");
  cmd->add_flag("--quiet", o->quiet, "no progress lines on stderr");
  cmd->callback([o, setExit] { setExit(optimise(*o)); });
}

}  // namespace virtcom::cli
