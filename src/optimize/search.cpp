// Exhaustive enumeration of distinct candidates and seeded simulated annealing, both batched.
#include "optimize/search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace virtcom::optimize {

double objectiveValue(Objective o, const Evaluation& e) {
  return o == Objective::Energy ? e.energyJ : static_cast<double>(e.cycleNs) * 1e-9;
}

namespace {

bool shareResource(const ProcessModel& m, uint32_t a, uint32_t b) {
  for (const Resource& r : m.resources)
    if (std::ranges::find(r.users, a) != r.users.end() && std::ranges::find(r.users, b) != r.users.end()) return true;
  return false;
}

int64_t deviceOf(const ProcessModel& m, const Candidate& c, uint32_t op) {
  return m.operations[op].alternatives[static_cast<size_t>(c.choice[op])].device;
}

// Orders of the present operations in lexicographic normal form: two adjacent operations that
// the PLC runs independently (other devices, no precedence, no shared resource) appear only in
// ascending order, which leaves one order per behaviour class (and a few repeats, removed by key).
class Enumerator {
 public:
  Enumerator(const ProcessModel& m, size_t limit) : m_(m), limit_(limit) {}

  std::vector<Candidate> run() {
    const size_t n = m_.operations.size();
    Candidate c;
    c.choice.assign(n, 0);
    chooseFrom(0, c);
    return std::move(out_);
  }

 private:
  bool full() const { return out_.size() > limit_; }

  void chooseFrom(size_t op, Candidate& c) {
    if (full()) return;
    if (op == m_.operations.size()) {
      placed_.assign(op, 0);
      c.order.clear();
      orderFrom(c);
      return;
    }
    const Operation& o = m_.operations[op];
    for (int a = o.optional ? kSkipped : 0; a < static_cast<int>(o.alternatives.size()); ++a) {
      c.choice[op] = a;
      chooseFrom(op + 1, c);
    }
  }

  bool available(const Candidate& c, uint32_t op) const {
    if (placed_[op] || c.choice[op] == kSkipped) return false;
    for (size_t p = 0; p < m_.operations.size(); ++p)
      if (m_.precedes[p][op] && !placed_[p] && c.choice[p] != kSkipped) return false;
    return true;
  }

  bool independent(const Candidate& c, uint32_t a, uint32_t b) const {
    return deviceOf(m_, c, a) != deviceOf(m_, c, b) && !m_.precedes[a][b] && !m_.precedes[b][a] && !shareResource(m_, a, b);
  }

  void orderFrom(Candidate& c) {
    if (full()) return;
    const uint32_t n = static_cast<uint32_t>(m_.operations.size());
    bool any = false;
    for (uint32_t op = 0; op < n; ++op) {
      if (!available(c, op)) continue;
      any = true;
      if (!c.order.empty() && op < c.order.back() && independent(c, c.order.back(), op)) continue;
      placed_[op] = 1;
      c.order.push_back(op);
      orderFrom(c);
      c.order.pop_back();
      placed_[op] = 0;
      if (full()) return;
    }
    if (any) return;
    if (c.order.size() + skippedCount(c) != n) return;  // a dead end of the normal form
    Candidate done = c;
    for (uint32_t op = 0; op < n; ++op)
      if (c.choice[op] == kSkipped) done.order.push_back(op);
    if (keys_.insert(buildJobList(m_, done).key).second) out_.push_back(std::move(done));
  }

  size_t skippedCount(const Candidate& c) const { return static_cast<size_t>(std::ranges::count(c.choice, kSkipped)); }

  const ProcessModel& m_;
  size_t limit_;
  std::vector<char> placed_;
  std::unordered_set<std::string> keys_;
  std::vector<Candidate> out_;
};

// The search's state shared by both methods: the cache of simulated behaviours, the best
// candidates, the Pareto front, the rejected reasons, the counters.
class Search {
 public:
  Search(const ProcessModel& m, const BatchEvaluator& evaluate, const SearchOptions& o) : m_(m), evaluate_(evaluate), o_(o), rng_(o.seed) {}

  SearchResult exhaustive(std::vector<Candidate> all, std::string why) {
    result_.method = Method::Exhaustive;
    result_.why = std::move(why);
    for (size_t at = 0; at < all.size() && !stopped();) {
      std::vector<Candidate> batch;
      for (; at < all.size() && batch.size() < o_.batch && result_.evaluations + batch.size() < o_.budgetEvals; ++at) batch.push_back(all[at]);
      evaluateBatch(batch);
    }
    result_.complete = result_.evaluations == all.size();
    return finish();
  }

  SearchResult anneal(std::string why) {
    result_.method = Method::Anneal;
    result_.why = std::move(why);
    Candidate current = randomCandidate();
    double currentCost = std::numeric_limits<double>::infinity();
    for (const UserSequence& s : m_.sequences)  // start from the best of the user's sequences
      if (s.candidate.waits == WaitRule::Needed && !s.candidate.ignoreResources && !stopped()) {
        auto eval = evaluateBatch({s.candidate});
        if (!eval.empty() && eval[0].feasible && cost(eval[0]) < currentCost) {
          current = withSkippedInPlace(s.candidate);
          currentCost = cost(eval[0]);
        }
      }
    uint64_t idleBatches = 0;
    while (!stopped()) {
      std::vector<Candidate> batch = neighbours(current);
      if (batch.empty()) {
        // Every neighbour tried is known: jump elsewhere; a space seen whole ends the search.
        if (++idleBatches > 50) break;
        current = randomCandidate();
        currentCost = std::numeric_limits<double>::infinity();
        continue;
      }
      idleBatches = 0;
      std::vector<Evaluation> evals = evaluateBatch(batch);
      const double temperature = 0.05 * (1.0 - static_cast<double>(result_.evaluations) / static_cast<double>(o_.budgetEvals)) + 1e-4;
      for (size_t i = 0; i < evals.size(); ++i) {
        const double c = evals[i].feasible ? cost(evals[i]) : std::numeric_limits<double>::infinity();
        const double delta = std::isinf(currentCost) ? -1 : (c - currentCost) / currentCost;
        if (delta <= 0 || (std::isfinite(c) && uniform() < std::exp(-delta / temperature))) {
          current = batch[i];
          currentCost = c;
        }
      }
      ++batches_;
    }
    return finish();
  }

 private:
  bool stopped() const { return result_.evaluations >= o_.budgetEvals || (o_.stop && o_.stop()); }

  double uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  size_t below(size_t n) { return static_cast<size_t>(rng_() % n); }

  // Time or energy; `both` weighs the two (relative to the first feasible run) with a weight
  // that turns with the batches, so the walk visits the whole front.
  double cost(const Evaluation& e) {
    if (o_.objective != Objective::Both) return objectiveValue(o_.objective, e);
    if (!reference_) reference_ = e;
    const double w = static_cast<double>(batches_ % 5) / 4.0;
    return w * static_cast<double>(e.cycleNs) / static_cast<double>(reference_->cycleNs) + (1 - w) * e.energyJ / reference_->energyJ;
  }

  // The same candidate with its skipped operations moved to where precedence allows them (a
  // user's sequence lists them last), the invariant mutate() keeps: an order valid over all
  // operations. Kahn's algorithm taking the earliest ready operation of the given order keeps
  // the order of the others.
  Candidate withSkippedInPlace(const Candidate& c) const {
    const size_t n = m_.operations.size();
    Candidate out = c;
    out.order.clear();
    std::vector<char> placed(n, 0);
    while (out.order.size() < n)
      for (uint32_t op : c.order) {
        bool ready = !placed[op];
        for (size_t p = 0; p < n && ready; ++p) ready = !(m_.precedes[p][op] && !placed[p]);
        if (!ready) continue;
        placed[op] = 1;
        out.order.push_back(op);
        break;
      }
    return out;
  }

  Candidate randomCandidate() {
    const size_t n = m_.operations.size();
    Candidate c;
    c.choice.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const Operation& op = m_.operations[i];
      const size_t options = op.alternatives.size() + (op.optional ? 1 : 0);
      c.choice[i] = static_cast<int>(below(options)) - (op.optional ? 1 : 0);
    }
    std::vector<char> placed(n, 0);
    while (c.order.size() < n) {
      std::vector<uint32_t> ready;
      for (uint32_t i = 0; i < n; ++i) {
        bool ok = !placed[i];
        for (size_t p = 0; p < n && ok; ++p) ok = !(m_.precedes[p][i] && !placed[p]);
        if (ok) ready.push_back(i);
      }
      const uint32_t pick = ready[below(ready.size())];
      placed[pick] = 1;
      c.order.push_back(pick);
    }
    return c;
  }

  // One random step: another alternative of an operation, or an operation moved to another place
  // between the last one it must follow and the first one that must follow it.
  void mutate(Candidate& c) {
    const size_t n = m_.operations.size();
    std::vector<uint32_t> choosable;
    for (uint32_t i = 0; i < n; ++i)
      if (m_.operations[i].alternatives.size() + (m_.operations[i].optional ? 1 : 0) > 1) choosable.push_back(i);
    if (!choosable.empty() && uniform() < 0.25) {
      const uint32_t op = choosable[below(choosable.size())];
      const Operation& o = m_.operations[op];
      const size_t options = o.alternatives.size() + (o.optional ? 1 : 0);
      c.choice[op] = static_cast<int>(below(options)) - (o.optional ? 1 : 0);
      return;
    }
    const uint32_t op = static_cast<uint32_t>(below(n));
    c.order.erase(std::ranges::find(c.order, op));
    size_t lo = 0, hi = c.order.size();
    for (size_t p = 0; p < c.order.size(); ++p) {
      if (m_.precedes[c.order[p]][op]) lo = p + 1;
      if (m_.precedes[op][c.order[p]] && hi == c.order.size()) hi = p;
    }
    lo = std::min(lo, hi);
    c.order.insert(c.order.begin() + static_cast<std::ptrdiff_t>(lo + below(hi - lo + 1)), op);
  }

  // Up to one batch of candidates near `from` whose behaviour has not been simulated yet.
  std::vector<Candidate> neighbours(const Candidate& from) {
    std::vector<Candidate> batch;
    std::unordered_set<std::string> inBatch;
    const size_t want = std::min<uint64_t>(o_.batch, o_.budgetEvals - result_.evaluations);
    for (size_t attempt = 0; attempt < o_.batch * 40 && batch.size() < want; ++attempt) {
      Candidate c = from;
      c.waits = WaitRule::Needed;
      c.ignoreResources = false;
      do mutate(c);
      while (uniform() < 0.3);
      std::string key = buildJobList(m_, c).key;
      if (cache_.contains(key) || !inBatch.insert(key).second) {
        ++result_.repeats;
        continue;
      }
      batch.push_back(std::move(c));
    }
    return batch;
  }

  std::vector<Evaluation> evaluateBatch(const std::vector<Candidate>& batch) {
    std::vector<JobList> lists;
    std::vector<size_t> toRun;
    std::vector<Evaluation> evals(batch.size());
    for (size_t i = 0; i < batch.size(); ++i) {
      lists.push_back(buildJobList(m_, batch[i]));
      if (auto it = cache_.find(lists.back().key); it != cache_.end()) evals[i] = it->second;
      else toRun.push_back(i);
    }
    std::vector<JobList> run;
    for (size_t i : toRun) run.push_back(lists[i]);
    std::vector<Evaluation> fresh = run.empty() ? std::vector<Evaluation>{} : evaluate_(run);
    for (size_t k = 0; k < toRun.size(); ++k) {
      const size_t i = toRun[k];
      evals[i] = fresh[k];
      cache_.emplace(lists[i].key, evals[i]);
      ++result_.evaluations;
      record({batch[i], lists[i], evals[i]});
    }
    if (o_.progress) {
      Progress p{result_.evaluations, result_.infeasible, bestSoFar(), front_.size()};
      o_.progress(p);
    }
    return evals;
  }

  const Scored* bestSoFar() const {
    if (o_.objective == Objective::Both) return front_.empty() ? nullptr : &front_.front();
    return best_.empty() ? nullptr : &best_.front();
  }

  void record(Scored s) {
    if (!s.eval.feasible) {
      ++result_.infeasible;
      const std::string kind = s.eval.reason.substr(0, s.eval.reason.find(' '));
      if (rejectedKinds_.insert(kind).second) result_.rejected.push_back(std::move(s));
      return;
    }
    if (o_.objective == Objective::Both) {
      for (const Scored& f : front_)
        if (f.eval.cycleNs <= s.eval.cycleNs && f.eval.energyJ <= s.eval.energyJ) return;  // dominated or equal
      std::erase_if(front_, [&](const Scored& f) { return s.eval.cycleNs <= f.eval.cycleNs && s.eval.energyJ <= f.eval.energyJ; });
      auto at = std::ranges::upper_bound(front_, s.eval.cycleNs, {}, [](const Scored& f) { return f.eval.cycleNs; });
      front_.insert(at, std::move(s));
      return;
    }
    const double v = objectiveValue(o_.objective, s.eval);
    auto at = std::ranges::upper_bound(best_, v, {}, [&](const Scored& b) { return objectiveValue(o_.objective, b.eval); });
    if (static_cast<size_t>(at - best_.begin()) >= o_.keep) return;
    best_.insert(at, std::move(s));
    if (best_.size() > o_.keep) best_.pop_back();
  }

  SearchResult finish() {
    result_.best = o_.objective == Objective::Both ? std::move(front_) : std::move(best_);
    return std::move(result_);
  }

  const ProcessModel& m_;
  const BatchEvaluator& evaluate_;
  const SearchOptions& o_;
  std::mt19937_64 rng_;
  std::unordered_map<std::string, Evaluation> cache_;
  std::vector<Scored> best_, front_;
  std::set<std::string> rejectedKinds_;
  std::optional<Evaluation> reference_;
  uint64_t batches_ = 0;
  SearchResult result_;
};

}  // namespace

std::vector<Candidate> enumerateCandidates(const ProcessModel& m, size_t limit) { return Enumerator(m, limit).run(); }

SearchResult search(const ProcessModel& m, const BatchEvaluator& evaluate, const SearchOptions& options) {
  Search s(m, evaluate, options);
  if (options.method == Method::Anneal) return s.anneal("--method anneal");
  // The evidence for the method: how many distinct candidates there are, counted up to the budget
  // (and at most kExhaustiveLimit: counting costs time of its own).
  const size_t limit = static_cast<size_t>(std::min<uint64_t>(options.budgetEvals, kExhaustiveLimit));
  std::vector<Candidate> all = enumerateCandidates(m, limit);
  const bool fits = all.size() <= limit;
  if (fits || options.method == Method::Exhaustive) {
    std::string why = fits ? std::to_string(all.size()) + " distinct candidates, within the budget of " + std::to_string(options.budgetEvals) +
                                 " evaluations: all evaluated"
                           : "--method exhaustive: the first " + std::to_string(limit) + " distinct candidates";
    if (!fits) all.pop_back();
    return s.exhaustive(std::move(all), std::move(why));
  }
  return s.anneal("more than " + std::to_string(limit) + " distinct candidates: simulated annealing");
}

}  // namespace virtcom::optimize
