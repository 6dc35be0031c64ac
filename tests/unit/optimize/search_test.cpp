// The search on models whose optimum is known by brute force, with a stand-in evaluator (a list
// scheduler of fixed durations) so that many models and seeds run in milliseconds; the real
// simulation is tested in evaluator_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>

#include "optimize/search.hpp"

namespace virtcom::optimize {
namespace {

Operation op(std::string name, int64_t device, int64_t code, std::vector<uint32_t> after = {}) {
  Operation o;
  o.name = std::move(name);
  o.alternatives.push_back({"d" + std::to_string(device), "d" + std::to_string(device), device, code});
  o.after = std::move(after);
  return o;
}

void close(ProcessModel& m) {
  const size_t n = m.operations.size();
  m.precedes.assign(n, std::vector<char>(n, 0));
  for (size_t i = 0; i < n; ++i)
    for (uint32_t a : m.operations[i].after) m.precedes[a][i] = 1;
  for (size_t k = 0; k < n; ++k)
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j)
        if (m.precedes[i][k] && m.precedes[k][j]) m.precedes[i][j] = 1;
}

// What the PLC does with a job list, with the job's code as its duration (s): each device runs
// its jobs in list order, each once the jobs it waits for are done. Device 3 cannot run code 3
// right after code 2 (a stand-in for a device error). Energy: 1 J per second of every job, plus
// 5 J per job on device 2 (a slow but thrifty device 1 makes time and energy disagree).
Evaluation schedule(const JobList& list) {
  std::map<int64_t, double> free;
  std::map<int64_t, int64_t> lastCode;
  std::vector<double> end(list.jobs.size());
  Evaluation e;
  double makespan = 0;
  for (size_t i = 0; i < list.jobs.size(); ++i) {
    const Job& j = list.jobs[i];
    if (j.device == 3 && j.code == 3 && lastCode[3] == 2) {
      e.reason = "device error: d3 cannot run 3 after 2";
      return e;
    }
    lastCode[j.device] = j.code;
    double start = free[j.device];
    for (uint32_t w : j.waits) start = std::max(start, end[w - 1]);
    end[i] = start + static_cast<double>(j.code);
    free[j.device] = end[i];
    makespan = std::max(makespan, end[i]);
    e.energyJ += static_cast<double>(j.code) + (j.device == 2 ? 5.0 : 0.0);
  }
  e.feasible = true;
  e.cycleNs = static_cast<int64_t>(makespan * 1e9);
  return e;
}

std::vector<Evaluation> scheduleAll(const std::vector<JobList>& lists) {
  std::vector<Evaluation> out;
  for (const auto& l : lists) out.push_back(schedule(l));
  return out;
}

// Every order of the operations (by permutation, independent of the search's enumeration) and
// every choice: the best value of the objective.
double bruteForce(const ProcessModel& m, Objective objective) {
  const size_t n = m.operations.size();
  std::vector<uint32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0u);
  std::vector<std::vector<int>> choices{{}};
  for (const Operation& o : m.operations) {
    std::vector<std::vector<int>> next;
    for (const auto& c : choices)
      for (int a = o.optional ? kSkipped : 0; a < static_cast<int>(o.alternatives.size()); ++a) {
        next.push_back(c);
        next.back().push_back(a);
      }
    choices = std::move(next);
  }
  double best = 1e300;
  do {
    for (const auto& choice : choices) {
      Candidate c{perm, choice, WaitRule::Needed, false};
      if (!checkCandidate(m, c).empty()) continue;
      Evaluation e = schedule(buildJobList(m, c));
      if (e.feasible) best = std::min(best, objectiveValue(objective, e));
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

// Seven operations on three devices, a resource, an alternative, an optional operation and a
// device-error pair: 5040 orders times 4 choices, brute-forced in well under a second.
ProcessModel sevenOperations() {
  ProcessModel m;
  m.operations = {op("a", 1, 3), op("b", 1, 2), op("c", 2, 4, {0}), op("d", 2, 1), op("e", 3, 2), op("f", 3, 3), op("g", 1, 1, {2})};
  m.operations[3].alternatives.push_back({"onD1", "d1", 1, 4});  // d: 1 s on device 2 (6 J) or 4 s on device 1 (4 J)
  m.operations[6].optional = true;
  m.resources.push_back({"table", {1, 3}});
  close(m);
  return m;
}

TEST(Search, ExhaustiveFindsTheBruteForceOptimumAndSaysItIsProven) {
  ProcessModel m = sevenOperations();
  SearchOptions o;
  o.budgetEvals = 5000;
  SearchResult r = search(m, scheduleAll, o);
  ASSERT_FALSE(r.best.empty());
  EXPECT_EQ(r.method, Method::Exhaustive);
  EXPECT_TRUE(r.complete);
  EXPECT_DOUBLE_EQ(objectiveValue(Objective::Time, r.best[0].eval), bruteForce(m, Objective::Time));
  EXPECT_LT(r.evaluations, 5040u) << "orders the program runs alike are evaluated once";
}

TEST(Search, AnnealingFindsTheBruteForceOptimumForEveryObjectiveWithoutEnumerating) {
  ProcessModel m = sevenOperations();
  for (Objective objective : {Objective::Time, Objective::Energy}) {
    SearchOptions o;
    o.objective = objective;
    o.method = Method::Anneal;
    o.budgetEvals = 400;
    SearchResult r = search(m, scheduleAll, o);
    ASSERT_FALSE(r.best.empty());
    EXPECT_DOUBLE_EQ(objectiveValue(objective, r.best[0].eval), bruteForce(m, objective)) << objectiveName(objective);
    EXPECT_LE(r.evaluations, 400u);
  }
}

TEST(Search, InfeasibleCandidatesAreRejectedWithTheirReasonAndNeverReported) {
  ProcessModel m = sevenOperations();
  SearchOptions o;
  o.budgetEvals = 5000;
  SearchResult r = search(m, scheduleAll, o);
  EXPECT_GT(r.infeasible, 0u);
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].eval.reason, "device error: d3 cannot run 3 after 2");
  for (const Scored& s : r.best) EXPECT_TRUE(s.eval.feasible);
}

TEST(Search, SameSeedAndBudgetGiveTheSameResultAnotherSeedMayNot) {
  ProcessModel m = sevenOperations();
  SearchOptions o;
  o.method = Method::Anneal;
  o.budgetEvals = 120;
  o.seed = 7;
  SearchResult a = search(m, scheduleAll, o);
  SearchResult b = search(m, scheduleAll, o);
  ASSERT_EQ(a.best.size(), b.best.size());
  for (size_t i = 0; i < a.best.size(); ++i) EXPECT_EQ(a.best[i].list.key, b.best[i].list.key);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.repeats, b.repeats);
}

TEST(Search, BothObjectivesGiveAParetoFrontOfNonDominatedCandidates) {
  ProcessModel m = sevenOperations();
  SearchOptions o;
  o.objective = Objective::Both;
  o.budgetEvals = 5000;
  SearchResult r = search(m, scheduleAll, o);
  ASSERT_GE(r.best.size(), 2u) << "d on device 1 is slower but saves energy";
  for (size_t i = 0; i < r.best.size(); ++i) {
    if (i > 0) {
      EXPECT_GT(r.best[i].eval.cycleNs, r.best[i - 1].eval.cycleNs);
      EXPECT_LT(r.best[i].eval.energyJ, r.best[i - 1].eval.energyJ);
    }
  }
  EXPECT_DOUBLE_EQ(objectiveValue(Objective::Time, r.best.front().eval), bruteForce(m, Objective::Time));
  EXPECT_DOUBLE_EQ(r.best.back().eval.energyJ, bruteForce(m, Objective::Energy));
}

TEST(Search, AutoAnnealsWhenTheDistinctCandidatesExceedTheBudget) {
  ProcessModel m = sevenOperations();
  SearchOptions o;
  o.budgetEvals = 10;
  SearchResult r = search(m, scheduleAll, o);
  EXPECT_EQ(r.method, Method::Anneal);
  EXPECT_NE(r.why.find("more than 10 distinct candidates"), std::string::npos) << r.why;
  EXPECT_LE(r.evaluations, 10u);
}

TEST(Search, EnumerationGivesEveryBehaviourOnce) {
  ProcessModel m = sevenOperations();
  std::vector<Candidate> all = enumerateCandidates(m, 100000);
  std::set<std::string> keys;
  for (const Candidate& c : all) {
    EXPECT_EQ(checkCandidate(m, c), "");
    EXPECT_TRUE(keys.insert(buildJobList(m, c).key).second);
  }
  // Brute force: the distinct keys of all 5040 orders times every choice.
  std::set<std::string> brute;
  std::vector<uint32_t> perm(m.operations.size());
  std::iota(perm.begin(), perm.end(), 0u);
  do
    for (int d = 0; d < 2; ++d)
      for (int g = kSkipped; g < 1; ++g) {
        Candidate c{perm, {0, 0, 0, d, 0, 0, g}, WaitRule::Needed, false};
        if (checkCandidate(m, c).empty()) brute.insert(buildJobList(m, c).key);
      }
  while (std::next_permutation(perm.begin(), perm.end()));
  EXPECT_EQ(keys, brute);
}

}  // namespace
}  // namespace virtcom::optimize
