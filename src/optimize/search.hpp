#pragma once
// Searching the candidates of a process model (docs/optimise.md "Search"): exhaustive when the
// model has no more distinct candidates than the evaluation budget (the optimum is then proven),
// simulated annealing over precedence-feasible orders and alternatives otherwise. Candidates are
// evaluated in batches of a fixed size through a BatchEvaluator (the simulation, or a test's
// function), and every random choice comes from one generator seeded with SearchOptions::seed,
// so the result depends on the seed and the budget, never on how many threads evaluate a batch.
// Two candidates with the same JobList::key are simulated once.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "optimize/evaluator.hpp"
#include "optimize/job_list.hpp"
#include "optimize/process_model.hpp"

namespace virtcom::optimize {

enum class Method { Auto, Exhaustive, Anneal };

// Auto counts distinct candidates up to the budget but never beyond this many.
inline constexpr size_t kExhaustiveLimit = 20'000;

struct Scored {
  Candidate candidate;
  JobList list;
  Evaluation eval;
};

struct Progress {
  uint64_t evaluations = 0;
  uint64_t infeasible = 0;
  const Scored* best = nullptr;  // by the objective (both: shortest cycle); null before a feasible one
  size_t frontSize = 0;
};

// Evaluates a batch; result i belongs to candidate i.
using BatchEvaluator = std::function<std::vector<Evaluation>(const std::vector<JobList>&)>;

struct SearchOptions {
  Objective objective = Objective::Time;
  uint64_t budgetEvals = 1000;  // simulations at most
  Method method = Method::Auto;
  uint64_t seed = 1;
  size_t batch = 16;            // candidates per batch: fixed, so results do not depend on threads
  size_t keep = 3;              // best candidates reported for time or energy
  std::function<bool()> stop;   // between batches: true ends the search (time budget, Ctrl-C)
  std::function<void(const Progress&)> progress;  // after every batch
};

struct SearchResult {
  Method method = Method::Exhaustive;
  std::string why;              // why that method (the evidence: the size of the space)
  uint64_t evaluations = 0;     // simulations run
  uint64_t infeasible = 0;
  uint64_t repeats = 0;         // candidates whose behaviour had been simulated already
  bool complete = false;        // every distinct candidate was evaluated: the optimum is proven
  std::vector<Scored> best;     // time/energy: the best `keep`, best first; both: the Pareto front by cycle
  std::vector<Scored> rejected; // the first infeasible candidate of every distinct kind of reason
};

SearchResult search(const ProcessModel& m, const BatchEvaluator& evaluate, const SearchOptions& options);

// The distinct candidates of `m` (by JobList::key) with WaitRule::Needed, in a fixed order; stops
// after `limit` + 1 of them (the caller then knows the space is larger than `limit`).
std::vector<Candidate> enumerateCandidates(const ProcessModel& m, size_t limit);

// The objective's value of a feasible evaluation (both: cycle time).
double objectiveValue(Objective o, const Evaluation& e);

}  // namespace virtcom::optimize
