#include "lang/sfc/chart_check.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <set>

#include "core/ascii.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::sfc::detail {

namespace diag = st::diag;

std::string nameKey(std::string_view name) { return asciiUpper(name); }

namespace {

std::string lineOf(SourceLocation loc) { return "line " + std::to_string(loc.line); }

// "transition 'T1'", or for an unnamed one "the transition FROM Idle TO (Fill, Heat)".
std::string transitionLabel(const Transition& t) {
  if (!t.name.empty()) return "transition '" + t.name + "'";
  auto steps = [](const std::vector<NamedRef>& refs) {
    std::string out;
    for (const NamedRef& r : refs) out += (out.empty() ? "" : ", ") + r.name;
    return refs.size() == 1 ? out : "(" + out + ")";
  };
  return "the transition FROM " + steps(t.from) + " TO " + steps(t.to);
}

void checkSteps(const Chart& chart, std::map<std::string, size_t>& index, Diagnostics& diags) {
  for (size_t i = 0; i < chart.steps.size(); ++i) {
    const Step& step = chart.steps[i];
    auto [it, fresh] = index.emplace(nameKey(step.name), i);
    if (!fresh)
      diags.error(diag::E403, step.loc, "step '" + step.name + "' is already declared at " +
                                            lineOf(chart.steps[it->second].loc) + "; step names must be unique");
    for (const ActionAssociation& a : step.actions) {
      bool needsTime = qualifierNeedsTime(a.qualifier);
      std::string q(qualifierSpelling(a.qualifier));
      if (needsTime && !a.duration)
        diags.error(diag::E404, a.loc, "qualifier " + q + " needs a duration, e.g. " + a.action.name + "(" + q + ", T#2s)");
      if (!needsTime && a.duration)
        diags.error(diag::E404, a.duration->loc, "qualifier " + q + " takes no duration; only L, D, SD, DS and SL do");
    }
  }
  if (chart.steps.empty()) diags.error(diag::E401, chart.loc, "the chart has no steps; declare an INITIAL_STEP");
}

// Each network (steps connected by transitions, whatever their direction) starts at exactly one
// INITIAL_STEP; a body may hold several networks, which then evolve side by side.
void checkNetworks(const Chart& chart, const std::map<std::string, size_t>& index, ResolvedChart& r,
                   Diagnostics& diags) {
  // A step declared twice (E403) is the first declaration for the transitions: skip the copy.
  auto duplicate = [&](size_t k) { return index.at(nameKey(chart.steps[k].name)) != k; };
  std::vector<size_t> network(chart.steps.size());
  for (size_t k = 0; k < network.size(); ++k) network[k] = k;
  auto root = [&](size_t k) {
    while (network[k] != k) k = network[k] = network[network[k]];
    return k;
  };
  for (size_t t = 0; t < chart.transitions.size(); ++t) {
    std::vector<size_t> ends = r.from[t];
    ends.insert(ends.end(), r.to[t].begin(), r.to[t].end());
    for (size_t k = 1; k < ends.size(); ++k) network[root(ends[k])] = root(ends[0]);
  }
  std::map<size_t, size_t> initialOf;  // network root -> its initial step
  for (size_t k = 0; k < chart.steps.size(); ++k) {
    if (!chart.steps[k].initial || duplicate(k)) continue;
    auto [it, fresh] = initialOf.emplace(root(k), k);
    if (fresh) {
      r.initials.push_back(k);
      continue;
    }
    const Step& first = chart.steps[it->second];
    diags.error(diag::E401, chart.steps[k].loc,
                "a second INITIAL_STEP '" + chart.steps[k].name + "' in the network that starts at '" + first.name +
                    "' (" + lineOf(first.loc) + "); each network of connected steps has exactly one initial step");
  }
  std::set<size_t> reported;
  for (size_t k = 0; k < chart.steps.size(); ++k)
    if (!duplicate(k) && !initialOf.count(root(k)) && reported.insert(root(k)).second)
      diags.error(diag::E401, chart.steps[k].loc,
                  "step '" + chart.steps[k].name + "' belongs to a network of steps without an INITIAL_STEP; "
                  "each network of connected steps has exactly one initial step");
}

void resolveSteps(const std::vector<NamedRef>& names, const Transition& t, std::string_view side,
                  const std::map<std::string, size_t>& index, std::vector<size_t>& out, Diagnostics& diags) {
  if (names.empty())
    diags.error(diag::E407, t.loc, transitionLabel(t) + " has no " + std::string(side) + " step");
  for (const NamedRef& n : names) {
    auto it = index.find(nameKey(n.name));
    if (it == index.end()) {
      diags.error(diag::E402, n.loc, "unknown step '" + n.name + "' in " + transitionLabel(t) + "; declare it with STEP " +
                                         n.name + ": ... END_STEP");
    } else if (std::find(out.begin(), out.end(), it->second) != out.end()) {
      diags.error(diag::E407, n.loc, "step '" + n.name + "' is listed twice " + std::string(side) + " " + transitionLabel(t));
    } else {
      out.push_back(it->second);
    }
  }
}

void checkTransitions(const Chart& chart, const std::map<std::string, size_t>& index, ResolvedChart& r,
                      Diagnostics& diags) {
  std::map<std::string, size_t> names;
  r.from.resize(chart.transitions.size());
  r.to.resize(chart.transitions.size());
  for (size_t i = 0; i < chart.transitions.size(); ++i) {
    const Transition& t = chart.transitions[i];
    if (!t.name.empty()) {
      auto [it, fresh] = names.emplace(nameKey(t.name), i);
      if (!fresh)
        diags.error(diag::E403, t.loc, "transition '" + t.name + "' is already declared at " +
                                           lineOf(chart.transitions[it->second].loc));
    }
    resolveSteps(t.from, t, "FROM", index, r.from[i], diags);
    resolveSteps(t.to, t, "TO", index, r.to[i], diags);
    if (!t.condition && t.body.empty())
      diags.error(diag::E407, t.loc, transitionLabel(t) + " has no condition; write ':= condition;' or an ST body");
    if (!t.condition && !t.body.empty() && t.name.empty())
      diags.error(diag::E407, t.loc, "a transition with an ST body needs a name, which the body assigns: "
                                     "TRANSITION T1 FROM a TO b : T1 := ...; END_TRANSITION");
  }
  r.priorityOrder.resize(chart.transitions.size());
  for (size_t i = 0; i < r.priorityOrder.size(); ++i) r.priorityOrder[i] = i;
  std::stable_sort(r.priorityOrder.begin(), r.priorityOrder.end(), [&](size_t a, size_t b) {
    const auto& pa = chart.transitions[a].priority;
    const auto& pb = chart.transitions[b].priority;
    if (pa.has_value() != pb.has_value()) return pa.has_value();
    return pa.has_value() && *pa < *pb;
  });
}

void checkActions(const Chart& chart, const std::vector<std::string>& pouActionNames, Diagnostics& diags) {
  std::set<std::string> seen;
  for (const std::string& n : pouActionNames) seen.insert(nameKey(n));
  for (const Action& a : chart.actions)
    if (!seen.insert(nameKey(a.name)).second)
      diags.error(diag::E403, a.loc, "action '" + a.name + "' is already declared; action names must be unique");
}

// A situation: the set of active steps, one bit per step.
using Situation = std::vector<uint64_t>;

bool has(const Situation& s, size_t step) { return (s[step / 64] >> (step % 64)) & 1u; }
void put(Situation& s, size_t step, bool on) {
  uint64_t bit = uint64_t{1} << (step % 64);
  s[step / 64] = on ? (s[step / 64] | bit) : (s[step / 64] & ~bit);
}

}  // namespace

std::optional<ResolvedChart> resolveChart(const Chart& chart, const std::vector<std::string>& pouActionNames,
                                          Diagnostics& diags) {
  size_t errorsBefore = diags.errorCount();
  ResolvedChart r;
  std::map<std::string, size_t> index;
  checkSteps(chart, index, diags);
  checkTransitions(chart, index, r, diags);
  checkNetworks(chart, index, r, diags);
  checkActions(chart, pouActionNames, diags);
  if (diags.errorCount() != errorsBefore) return std::nullopt;
  return r;
}

bool analyseChart(const Chart& chart, const ResolvedChart& r, Diagnostics& diags) {
  size_t words = (chart.steps.size() + 63) / 64;
  Situation start(words, 0);
  for (size_t k : r.initials) put(start, k, true);
  std::set<Situation> seen{start};
  std::deque<Situation> queue{start};
  std::vector<bool> stepReached(chart.steps.size(), false), transitionEnabled(chart.transitions.size(), false);
  std::vector<bool> unsafeReported(chart.transitions.size(), false);
  bool ok = true;
  size_t firings = 0;
  while (!queue.empty() && firings < kMaxFirings) {
    Situation s = std::move(queue.front());
    queue.pop_front();
    for (size_t k = 0; k < chart.steps.size(); ++k) stepReached[k] = stepReached[k] || has(s, k);
    for (size_t t = 0; t < chart.transitions.size(); ++t) {
      if (!std::all_of(r.from[t].begin(), r.from[t].end(), [&](size_t k) { return has(s, k); })) continue;
      transitionEnabled[t] = true;
      ++firings;
      Situation next = s;
      for (size_t k : r.from[t]) put(next, k, false);
      for (size_t k : r.to[t]) {
        if (has(next, k) && !unsafeReported[t]) {
          unsafeReported[t] = true;
          ok = false;
          diags.error(diag::E405, chart.transitions[t].loc,
                      "unsafe chart: " + transitionLabel(chart.transitions[t]) + " can activate step '" +
                          chart.steps[k].name + "' while it is still active (a jump into or out of a parallel "
                          "branch?); close parallel branches with one transition FROM (all branch ends)");
        }
        put(next, k, true);
      }
      if (seen.size() < kMaxSituations && seen.insert(next).second) queue.push_back(std::move(next));
    }
  }
  bool complete = seen.size() < kMaxSituations && firings < kMaxFirings;
  if (!complete) return ok;  // not explored completely: no unreachability verdict
  for (size_t k = 0; k < chart.steps.size(); ++k) {
    if (stepReached[k]) continue;
    ok = false;
    diags.error(diag::E406, chart.steps[k].loc, "step '" + chart.steps[k].name +
                                                    "' can never become active: no sequence of transitions "
                                                    "from the initial steps reaches it");
  }
  for (size_t t = 0; t < chart.transitions.size(); ++t) {
    if (transitionEnabled[t]) continue;
    bool sourcesReached = std::all_of(r.from[t].begin(), r.from[t].end(), [&](size_t k) { return stepReached[k]; });
    if (!sourcesReached) continue;  // its unreachable source step is reported already
    ok = false;
    diags.error(diag::E406, chart.transitions[t].loc,
                transitionLabel(chart.transitions[t]) + " can never fire: its source steps are never active at the "
                "same time (a simultaneous convergence of selective branches?)");
  }
  return ok;
}

}  // namespace virtcom::sfc::detail
