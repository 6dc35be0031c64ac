// Candidates simulated by the real PLC program on the real cell: the gearbox's four hand-written
// sequences as orderings of its process model, infeasible candidates with their reasons, the
// search on a small cell against brute force, and results independent of the thread count.
#include <gtest/gtest.h>

#include <numeric>
#include <set>

#include "cell/cell.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/search.hpp"
#include "report/kpis.hpp"
#include "sim/simulation.hpp"

namespace virtcom::optimize {
namespace {

const std::string kData = VIRTCOM_SOURCE_DIR "/tests/unit/optimize/data/";
const std::string kGearbox = VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/";

struct Loaded {
  SourceManager sources;
  Diagnostics diags;
  std::optional<ProcessModel> model;
  std::unique_ptr<Evaluator> evaluator;
};

std::unique_ptr<Loaded> load(const std::string& path) {
  auto l = std::make_unique<Loaded>();
  l->model = readProcessModel(path, l->sources, l->diags);
  if (l->model) l->evaluator = Evaluator::create(*l->model, l->sources, l->diags);
  EXPECT_TRUE(l->evaluator) << l->diags.render(l->sources);
  return l;
}

// `virtcom run cell.yaml --set MAIN.sequence=N`, as the run command does it.
Trace runSequence(int sequence) {
  SourceManager sources;
  Diagnostics diags;
  auto cell = cell::loadCell(kGearbox + "cell.yaml", sources, diags);
  EXPECT_TRUE(cell) << diags.render(sources);
  sim::SimOptions options;
  options.preset = [&](plc::Runtime& plc) {
    bc::writeValueFromText(*cell->module, *bc::resolveVariable(*cell->module, "MAIN.sequence"), std::to_string(sequence), plc.machine().memory());
  };
  sim::Simulation(*cell, options).run();
  return cell->trace;
}

TEST(GearboxModel, EachHandWrittenSequenceIsAnOrderingOfTheModelWithTheSameResult) {
  auto l = load(kGearbox + "process.yaml");
  ASSERT_TRUE(l->evaluator);
  const ProcessModel& m = *l->model;
  ASSERT_EQ(m.sequences.size(), 4u);
  for (int n = 1; n <= 4; ++n) {
    const Trace reference = runSequence(n);
    const report::Kpis kpis = report::computeKpis(reference);
    Evaluation e;
    auto cell = l->evaluator->run(buildJobList(m, m.sequences[n - 1].candidate), e);
    ASSERT_TRUE(cell) << n;
    EXPECT_EQ(cell->trace.end, reference.end) << "sequence " << n;
    // Sequence 1 screws studs 1-2 earlier in its (serial) list: every job lasts as long, but a
    // job is noticed one scan later where it follows a job of a device the PLC loop visits after
    // its own (plc/main.st steps devices 1..5): two such places, 20 ms. The others are exact.
    const int64_t scansNs = n == 1 ? 20'000'000 : 0;
    EXPECT_NEAR(cell->trace.endNs, reference.endNs, scansNs) << "sequence " << n;
    if (n < 4) {
      EXPECT_TRUE(e.feasible) << n << ": " << e.reason;
      EXPECT_NEAR(e.cycleNs, kpis.cycleTimeNs, scansNs) << "sequence " << n;
      EXPECT_NEAR(e.energyJ, kpis.totalEnergyJ, n == 1 ? 0.001 * kpis.totalEnergyJ : 1e-6) << "sequence " << n;
    } else {
      EXPECT_FALSE(e.feasible);
      EXPECT_EQ(e.reason, "collision at 33.280 s: robots collided in a shared zone");
    }
  }
}

TEST(Evaluator, InfeasibleCandidatesCarryTheirReason) {
  auto l = load(kData + "two_robots_model.yaml");
  ASSERT_TRUE(l->evaluator);
  const ProcessModel& m = *l->model;
  Evaluation collided = l->evaluator->evaluate(buildJobList(m, m.sequences[1].candidate));
  EXPECT_FALSE(collided.feasible);
  EXPECT_EQ(collided.reason.substr(0, 13), "collision at ") << collided.reason;

  JobList deadlock;  // two jobs waiting for each other
  deadlock.jobs = {{0, 1, 2, {2}}, {1, 2, 2, {1}}};
  Evaluation stuck = l->evaluator->evaluate(deadlock);
  EXPECT_EQ(stuck.reason, "deadlock: no completed cycle within 30.000 s (0 of 2 jobs finished)");

  JobList unknown;  // procedure 7 does not exist on R1
  unknown.jobs = {{0, 1, 7, {}}};
  Evaluation error = l->evaluator->evaluate(unknown);
  EXPECT_FALSE(error.feasible);
  EXPECT_NE(error.reason.find("device error at "), std::string::npos) << error.reason;
  EXPECT_NE(error.reason.find("R1 reported error 10 (unknown procedure/program number"), std::string::npos) << error.reason;

  JobList tooManyWaits;
  tooManyWaits.jobs = {{0, 1, 1, {}}, {1, 2, 1, {}}, {2, 1, 1, {}}, {3, 2, 1, {1, 2, 3}}};
  EXPECT_EQ(l->evaluator->evaluate(tooManyWaits).reason, "job D must wait for 3 jobs; the job list has 2 wait fields");
}

TEST(Evaluator, FeasibleCandidateHasTheCycleOfItsSchedule) {
  auto l = load(kData + "two_robots_model.yaml");
  ASSERT_TRUE(l->evaluator);
  const ProcessModel& m = *l->model;
  Evaluation e = l->evaluator->evaluate(buildJobList(m, m.sequences[0].candidate));
  ASSERT_TRUE(e.feasible) << e.reason;
  EXPECT_GT(e.cycleNs, 7'000'000'000);  // at least A (3 s) + B (1 s and its moves) + C (1 s) + E (1 s) on the critical path
  EXPECT_GT(e.energyJ, 0);
  EXPECT_EQ(l->evaluator->evaluate(buildJobList(m, m.sequences[0].candidate)).cycleNs, e.cycleNs) << "a fresh cell every time";
}

// Brute force over every order and choice (distinct behaviours simulated once): the search's
// exhaustive and annealing methods must both reach its optimum.
TEST(Evaluator, SearchFindsTheBruteForceOptimumOfTheSimulatedCell) {
  auto l = load(kData + "two_robots_model.yaml");
  ASSERT_TRUE(l->evaluator);
  const ProcessModel& m = *l->model;
  std::set<std::string> seen;
  std::vector<JobList> lists;
  std::vector<uint32_t> perm(m.operations.size());
  std::iota(perm.begin(), perm.end(), 0u);
  do
    for (int e = 0; e < 2; ++e)
      for (int f = kSkipped; f < 1; ++f) {
        Candidate c{perm, {0, 0, 0, 0, e, f}, WaitRule::Needed, false};
        if (!checkCandidate(m, c).empty()) continue;
        JobList list = buildJobList(m, c);
        if (seen.insert(list.key).second) lists.push_back(std::move(list));
      }
  while (std::next_permutation(perm.begin(), perm.end()));
  int64_t best = INT64_MAX;
  for (const Evaluation& e : evaluateAll(*l->evaluator, lists, 2))
    if (e.feasible) best = std::min(best, e.cycleNs);
  ASSERT_LT(best, INT64_MAX);
  BatchEvaluator batch = [&](const std::vector<JobList>& b) { return evaluateAll(*l->evaluator, b, 2); };
  for (Method method : {Method::Auto, Method::Anneal}) {
    SearchOptions o;
    o.method = method;
    o.budgetEvals = 200;
    SearchResult r = search(m, batch, o);
    ASSERT_FALSE(r.best.empty());
    EXPECT_EQ(r.best[0].eval.cycleNs, best) << (method == Method::Auto ? "auto" : "anneal");
  }
}

TEST(Evaluator, ResultDoesNotDependOnTheNumberOfThreads) {
  auto l = load(kData + "two_robots_model.yaml");
  ASSERT_TRUE(l->evaluator);
  std::vector<SearchResult> results;
  for (unsigned threads : {1u, 3u}) {
    BatchEvaluator batch = [&](const std::vector<JobList>& b) { return evaluateAll(*l->evaluator, b, threads); };
    SearchOptions o;
    o.method = Method::Anneal;
    o.budgetEvals = 40;
    o.seed = 3;
    o.keep = 5;
    results.push_back(search(*l->model, batch, o));
  }
  ASSERT_EQ(results[0].best.size(), results[1].best.size());
  for (size_t i = 0; i < results[0].best.size(); ++i) {
    EXPECT_EQ(results[0].best[i].list.key, results[1].best[i].list.key);
    EXPECT_EQ(results[0].best[i].eval.cycleNs, results[1].best[i].eval.cycleNs);
  }
  EXPECT_EQ(results[0].evaluations, results[1].evaluations);
  EXPECT_EQ(results[0].infeasible, results[1].infeasible);
}

}  // namespace
}  // namespace virtcom::optimize
