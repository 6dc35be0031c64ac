// Lowering of a chart into ST statements and variables; the semantics are in lower.hpp.
#include "lang/sfc/lower.hpp"

#include <algorithm>
#include <set>

#include "lang/sfc/chart_check.hpp"
#include "lang/syntax/ast_builder.hpp"
#include "lang/syntax/ast_clone.hpp"

namespace virtcom::sfc {

namespace {

using st::AstBuilder;
using detail::nameKey;
using st::BinaryOp;

// One action of the chart with every step association that drives it.
struct ActionUse {
  std::string name;
  SourceLocation loc;
  bool hasBody = false;  // an ACTION (called), else a BOOL variable (assigned)
  std::vector<std::pair<size_t, ActionAssociation*>> uses;  // (step index, association)
};

std::string hiddenName(std::string_view kind, size_t index, std::string_view suffix = "") {
  return "__sfc_" + std::string(kind) + std::to_string(index) + std::string(suffix);
}

bool wantsTransientChaining(const st::Pou& pou) {
  for (const st::Attribute& a : pou.attributes)
    if (nameKey(a.name) == nameKey(kTransientChainingAttribute)) return true;
  return false;
}

class Lowering {
 public:
  Lowering(Chart& chart, const detail::ResolvedChart& r, st::Pou& pou, st::NodeId& nextNodeId)
      : chart_(chart), r_(r), pou_(pou), b_(nextNodeId), chaining_(wantsTransientChaining(pou)) {
    b_.generated(true);
  }

  void run() {
    collectActions();
    b_.at(chart_.loc);
    hide("__sfc_init", "BOOL");
    hide("__sfc_now", "LTIME");
    st::StmtList code = clearEdgeFlags();
    code.push_back(b_.assign(b_.name("__sfc_now"), b_.call("__SYSTIME_NS", nullptr)));
    if (chaining_) {
      code.push_back(b_.ifThenElse(b_.notOf(b_.name("__sfc_init")), firstCall(), advanceTimes()));
      code.push_back(chainedEvolution());
    } else {
      st::StmtList later = advanceTimes();
      for (st::StmtPtr& s : evolution()) later.push_back(std::move(s));
      code.push_back(b_.ifThenElse(b_.notOf(b_.name("__sfc_init")), firstCall(), std::move(later)));
    }
    for (size_t j = 0; j < actions_.size(); ++j)
      for (st::StmtPtr& s : actionControl(j)) code.push_back(std::move(s));
    declareSteps();
    for (auto& s : code) pou_.body.push_back(std::move(s));
    pou_.varBlocks.push_back(std::move(hidden_));
    for (Action& a : chart_.actions) {
      auto action = std::make_unique<st::Pou>();
      action->kind = st::PouKind::Action;
      action->name = a.name;
      action->loc = a.loc;
      action->endLoc = a.loc;
      action->hasBody = true;
      action->body = std::move(a.body);
      pou_.actions.push_back(std::move(action));
    }
  }

 private:
  const std::string& stepName(size_t k) const { return chart_.steps[k].name; }
  st::ExprPtr stepX(size_t k) { return b_.member(stepName(k), "X"); }
  st::ExprPtr stepT(size_t k) { return b_.member(stepName(k), "T"); }

  void hide(std::string_view name, std::string_view type) {
    hidden_.vars.push_back(b_.varDecl(name, type, true));
  }

  // Groups the associations by action, and notes the steps that need edge flags: only those
  // whose activation (P, P1) or deactivation (P0) drives an action get them.
  void collectActions() {
    std::set<std::string> bodies;
    for (const auto& a : pou_.actions) bodies.insert(nameKey(a->name));
    for (const Action& a : chart_.actions) bodies.insert(nameKey(a.name));
    for (size_t k = 0; k < chart_.steps.size(); ++k) {
      for (ActionAssociation& assoc : chart_.steps[k].actions) {
        std::string key = nameKey(assoc.action.name);
        size_t j = 0;
        while (j < actions_.size() && nameKey(actions_[j].name) != key) ++j;
        if (j == actions_.size()) actions_.push_back({assoc.action.name, assoc.action.loc, bodies.count(key) > 0, {}});
        actions_[j].uses.emplace_back(k, &assoc);
        Qualifier q = assoc.qualifier;
        if (q == Qualifier::P || q == Qualifier::P1) risingFlag_.insert(k);
        if (q == Qualifier::P0) fallingFlag_.insert(k);
      }
    }
  }

  st::StmtList clearEdgeFlags() {
    st::StmtList out;
    for (size_t k : risingFlag_) {
      hide(hiddenName("s", k, "_new"), "BOOL");
      out.push_back(b_.assign(b_.name(hiddenName("s", k, "_new")), b_.boolLit(false)));
    }
    for (size_t k : fallingFlag_) {
      hide(hiddenName("s", k, "_end"), "BOOL");
      out.push_back(b_.assign(b_.name(hiddenName("s", k, "_end")), b_.boolLit(false)));
    }
    return out;
  }

  // Time since `startVar` (an LTIME set from __sfc_now) as TIME: measured from a start instant
  // rather than summed per call, so sub-millisecond cycles do not lose time to TIME's ms unit.
  st::ExprPtr elapsedSince(const std::string& startVar) {
    return b_.call("LTIME_TO_TIME", b_.binary(BinaryOp::Sub, b_.name("__sfc_now"), b_.name(startVar)));
  }

  // `st.cover`: the statement coverage counts as the activation of step k / the firing of
  // transition t (docs/coverage.md).
  void markStep(st::Stmt& st, size_t k) {
    st.cover = st::CoverRole::StepActivated;
    st.coverName = chart_.steps[k].name;
    st.coverLoc = chart_.steps[k].loc;
  }
  void markTransition(st::Stmt& st, size_t t) {
    const Transition& tr = chart_.transitions[t];
    st.cover = st::CoverRole::TransitionFired;
    st.coverLoc = tr.loc;
    st.coverName = tr.name;
    if (!st.coverName.empty()) return;
    // An unnamed transition is known by the steps it links: "Fill,Mix->Drain".
    for (size_t k : r_.from[t]) st.coverName += (st.coverName.empty() ? "" : ",") + stepName(k);
    st.coverName += "->";
    for (size_t i = 0; i < r_.to[t].size(); ++i) st.coverName += (i ? "," : "") + stepName(r_.to[t][i]);
  }

  void activate(size_t k, st::StmtList& out) {
    out.push_back(b_.assign(stepX(k), b_.boolLit(true)));
    markStep(*out.back(), k);
    out.push_back(b_.assign(stepT(k), b_.timeLit(0)));
    out.push_back(b_.assign(b_.name(hiddenName("s", k, "_start")), b_.name("__sfc_now")));
    if (risingFlag_.count(k)) out.push_back(b_.assign(b_.name(hiddenName("s", k, "_new")), b_.boolLit(true)));
  }

  void deactivate(size_t k, st::StmtList& out) {
    out.push_back(b_.assign(stepX(k), b_.boolLit(false)));
    if (fallingFlag_.count(k)) out.push_back(b_.assign(b_.name(hiddenName("s", k, "_end")), b_.boolLit(true)));
  }

  st::StmtList firstCall() {
    b_.at(chart_.steps[r_.initials.front()].loc);
    st::StmtList out;
    out.push_back(b_.assign(b_.name("__sfc_init"), b_.boolLit(true)));
    for (size_t k : r_.initials) activate(k, out);
    return out;
  }

  st::StmtList advanceTimes() {
    st::StmtList out;
    for (size_t k = 0; k < chart_.steps.size(); ++k) {
      b_.at(chart_.steps[k].loc);
      st::StmtList advance;
      advance.push_back(b_.assign(stepT(k), elapsedSince(hiddenName("s", k, "_start"))));
      out.push_back(b_.ifThen(stepX(k), std::move(advance)));
    }
    return out;
  }

  // FOR __sfc_pass := 1 TO <steps> DO <evolution> IF NOT (t0 OR t1 ...) THEN EXIT; END_IF
  // END_FOR. Bounded by the number of steps: a cycle of always-clear transitions cannot hang
  // the scan; what is left of it goes on in the next call.
  st::StmtPtr chainedEvolution() {
    b_.at(chart_.loc);
    hide("__sfc_pass", "DINT");
    st::StmtList pass = evolution();
    b_.at(chart_.loc);
    st::ExprPtr fired;
    for (size_t t : r_.priorityOrder) fired = b_.orElseNull(std::move(fired), b_.name(hiddenName("t", t)));
    if (!fired) fired = b_.boolLit(false);  // a chart of one step without transitions
    st::StmtList stop;
    stop.push_back(b_.exitLoop());
    pass.push_back(b_.ifThen(b_.notOf(std::move(fired)), std::move(stop)));
    return b_.forLoop("__sfc_pass", 1, chart_.steps.size(), std::move(pass));
  }

  // One evolution: every transition evaluated on the activity at its start, then fired.
  st::StmtList evolution() {
    st::StmtList out;
    for (size_t t : r_.priorityOrder) evaluate(t, out);
    // All deactivations before all activations: a step both left and entered stays active.
    for (size_t t : r_.priorityOrder) {
      b_.at(chart_.transitions[t].loc);
      st::StmtList body;
      for (size_t k : r_.from[t]) deactivate(k, body);
      if (!body.empty()) markTransition(*body.front(), t);
      out.push_back(b_.ifThen(b_.name(hiddenName("t", t)), std::move(body)));
    }
    for (size_t t : r_.priorityOrder) {
      b_.at(chart_.transitions[t].loc);
      st::StmtList body;
      for (size_t k : r_.to[t]) activate(k, body);
      out.push_back(b_.ifThen(b_.name(hiddenName("t", t)), std::move(body)));
    }
    return out;
  }

  // __sfc_tN := FALSE; IF <sources active> AND NOT <a higher-priority rival fired> THEN
  // __sfc_tN := condition; END_IF
  void evaluate(size_t t, st::StmtList& out) {
    Transition& tr = chart_.transitions[t];
    b_.at(tr.loc);
    std::string flag = hiddenName("t", t);
    hide(flag, "BOOL");
    st::ExprPtr guard;
    for (size_t k : r_.from[t]) guard = guard ? b_.binary(BinaryOp::And, std::move(guard), stepX(k)) : stepX(k);
    for (size_t rival : r_.priorityOrder) {
      if (rival == t) break;
      bool shares = false;
      for (size_t k : r_.from[rival]) shares = shares || std::find(r_.from[t].begin(), r_.from[t].end(), k) != r_.from[t].end();
      if (shares) guard = b_.binary(BinaryOp::And, std::move(guard), b_.notOf(b_.name(hiddenName("t", rival))));
    }
    st::StmtList fire;
    if (tr.condition) {
      fire.push_back(b_.assign(b_.name(flag), std::move(tr.condition)));
    } else {
      hidden_.vars.push_back(b_.varDecl(tr.name, "BOOL", false));  // the body assigns it: keep it visible
      fire.push_back(b_.assign(b_.name(tr.name), b_.boolLit(false)));
      for (st::StmtPtr& s : tr.body) fire.push_back(std::move(s));
      b_.at(tr.loc);
      fire.push_back(b_.assign(b_.name(flag), b_.name(tr.name)));
    }
    out.push_back(b_.assign(b_.name(flag), b_.boolLit(false)));
    out.push_back(b_.ifThen(std::move(guard), std::move(fire)));
  }

  // The terms of one action's control, collected over its associations.
  struct Control {
    st::StmtList sets;            // statements that set stored flags (run before the resets)
    st::StmtList resets;          // what R clears
    st::ExprPtr held;             // OR of the non-pulse terms (null: none)
    st::ExprPtr pulse;            // OR of the P, P0, P1 terms (null: none)
    std::vector<size_t> resetSteps;
    bool hasSet = false;
  };

  // Action control of IEC 61131-3 for action j: stored flags are set first and reset after
  // (R dominates), then Q = NOT R AND (held terms OR pulses).
  st::StmtList actionControl(size_t j) {
    ActionUse& a = actions_[j];
    Control c;
    for (size_t u = 0; u < a.uses.size(); ++u) addTerm(j, u, c);
    b_.at(a.loc);
    std::string setFlag = hiddenName("a", j, "_s");
    if (c.hasSet) {
      hide(setFlag, "BOOL");
      c.held = b_.orElseNull(std::move(c.held), b_.name(setFlag));
      c.resets.push_back(b_.assign(b_.name(setFlag), b_.boolLit(false)));
    }
    st::StmtList out = std::move(c.sets);
    if (!c.resetSteps.empty() && !c.resets.empty()) out.push_back(b_.ifThen(resetOf(c), std::move(c.resets)));
    std::string q = hiddenName("a", j, "_q");
    hide(q, "BOOL");
    st::ExprPtr pulse = c.pulse ? gated(c, std::move(c.pulse)) : nullptr;
    if (!a.hasBody) {
      out.push_back(b_.assign(b_.name(q), b_.orElseNull(gated(c, std::move(c.held)), std::move(pulse))));
      out.push_back(b_.assign(b_.name(a.name), b_.name(q)));
      return out;
    }
    // A body action held by a non-pulse qualifier runs once more after Q falls (the final scan).
    std::string held = hiddenName("a", j, "_held"), now = hiddenName("a", j, "_c");
    hide(held, "BOOL");
    hide(now, "BOOL");
    out.push_back(b_.assign(b_.name(now), gated(c, std::move(c.held))));
    out.push_back(b_.assign(b_.name(q), b_.orElseNull(b_.name(now), std::move(pulse))));
    st::StmtList call;
    call.push_back(b_.callStmt(a.name));
    out.push_back(b_.ifThen(b_.binary(BinaryOp::Or, b_.name(q), b_.name(held)), std::move(call)));
    out.push_back(b_.assign(b_.name(held), b_.name(now)));
    return out;
  }

  st::ExprPtr resetOf(const Control& c) {
    st::ExprPtr e;
    for (size_t k : c.resetSteps) e = b_.orElseNull(std::move(e), stepX(k));
    return e;
  }

  // NOT R AND term (just term without R associations; FALSE for no term).
  st::ExprPtr gated(const Control& c, st::ExprPtr term) {
    if (!term) return b_.boolLit(false);
    if (c.resetSteps.empty()) return term;
    return b_.binary(BinaryOp::And, b_.notOf(resetOf(c)), std::move(term));
  }

  st::ExprPtr timed(size_t k, BinaryOp cmp, st::ExprPtr duration) {
    return b_.binary(BinaryOp::And, stepX(k), b_.binary(cmp, stepT(k), std::move(duration)));
  }

  // Adds association u of action j (of step k) to the control terms.
  void addTerm(size_t j, size_t u, Control& c) {
    auto [k, assoc] = actions_[j].uses[u];
    b_.at(assoc->loc);
    std::string stored = hiddenName("a", j, "_" + std::to_string(u) + "_m");
    std::string since = hiddenName("a", j, "_" + std::to_string(u) + "_start");
    switch (assoc->qualifier) {
      case Qualifier::N: c.held = b_.orElseNull(std::move(c.held), stepX(k)); break;
      case Qualifier::L: c.held = b_.orElseNull(std::move(c.held), timed(k, BinaryOp::Lt, std::move(assoc->duration))); break;
      case Qualifier::D: c.held = b_.orElseNull(std::move(c.held), timed(k, BinaryOp::Ge, std::move(assoc->duration))); break;
      case Qualifier::P: case Qualifier::P1:
        c.pulse = b_.orElseNull(std::move(c.pulse), b_.name(hiddenName("s", k, "_new")));
        break;
      case Qualifier::P0: c.pulse = b_.orElseNull(std::move(c.pulse), b_.name(hiddenName("s", k, "_end"))); break;
      case Qualifier::S: {
        c.hasSet = true;
        st::StmtList set;
        set.push_back(b_.assign(b_.name(hiddenName("a", j, "_s")), b_.boolLit(true)));
        c.sets.push_back(b_.ifThen(stepX(k), std::move(set)));
        break;
      }
      case Qualifier::R: c.resetSteps.push_back(k); break;
      case Qualifier::SD: case Qualifier::SL: {
        hide(stored, "BOOL");
        hide(since, "LTIME");
        c.sets.push_back(store(stepX(k), stored, since));
        BinaryOp cmp = assoc->qualifier == Qualifier::SD ? BinaryOp::Ge : BinaryOp::Lt;
        st::ExprPtr on = b_.binary(cmp, elapsedSince(since), std::move(assoc->duration));
        c.held = b_.orElseNull(std::move(c.held), b_.binary(BinaryOp::And, b_.name(stored), std::move(on)));
        c.resets.push_back(b_.assign(b_.name(stored), b_.boolLit(false)));
        break;
      }
      case Qualifier::DS: {
        hide(stored, "BOOL");
        st::StmtList set;
        set.push_back(b_.assign(b_.name(stored), b_.boolLit(true)));
        c.sets.push_back(b_.ifThen(timed(k, BinaryOp::Ge, std::move(assoc->duration)), std::move(set)));
        c.held = b_.orElseNull(std::move(c.held), b_.name(stored));
        c.resets.push_back(b_.assign(b_.name(stored), b_.boolLit(false)));
        break;
      }
    }
  }

  // SD/SL: the step stores the action and starts its timer; later activations do not restart it.
  // IF NOT stored AND X THEN stored := TRUE; since := __sfc_now; END_IF
  st::StmtPtr store(st::ExprPtr x, const std::string& stored, const std::string& since) {
    st::StmtList body;
    body.push_back(b_.assign(b_.name(stored), b_.boolLit(true)));
    body.push_back(b_.assign(b_.name(since), b_.name("__sfc_now")));
    return b_.ifThen(b_.binary(BinaryOp::And, b_.notOf(b_.name(stored)), std::move(x)), std::move(body));
  }

  void declareSteps() {
    st::VarBlock steps;
    for (size_t k = 0; k < chart_.steps.size(); ++k) {
      b_.at(chart_.steps[k].loc);
      steps.vars.push_back(b_.varDecl(stepName(k), kStepTypeName, false));
      hide(hiddenName("s", k, "_start"), "LTIME");
    }
    steps.loc = chart_.loc;
    pou_.varBlocks.push_back(std::move(steps));
  }

  Chart& chart_;
  const detail::ResolvedChart& r_;
  st::Pou& pou_;
  AstBuilder b_;
  bool chaining_;
  st::VarBlock hidden_;
  std::vector<ActionUse> actions_;
  std::set<size_t> risingFlag_, fallingFlag_;
};

std::vector<ActionAssociation> copyOf(const std::vector<ActionAssociation>& src) {
  std::vector<ActionAssociation> out;
  for (const auto& a : src) out.push_back({a.action, a.qualifier, st::cloneExprOrNull(a.duration), a.indicator, a.loc});
  return out;
}

// The chart as written, for the exporter: lowering moves its expressions into the POU.
std::shared_ptr<const Chart> copyOf(const Chart& src) {
  auto c = std::make_shared<Chart>();
  c->loc = src.loc;
  for (const auto& s : src.steps) c->steps.push_back({s.name, s.loc, s.initial, copyOf(s.actions)});
  for (const auto& t : src.transitions)
    c->transitions.push_back({t.name, t.loc, t.priority, t.from, t.to, st::cloneExprOrNull(t.condition), st::cloneStatements(t.body)});
  for (const auto& a : src.actions) c->actions.push_back({a.name, a.loc, st::cloneStatements(a.body)});
  return c;
}

}  // namespace

void lowerChart(Chart chart, st::Pou& pou, Diagnostics& diags, st::NodeId& nextNodeId) {
  std::vector<std::string> pouActions;
  for (const auto& a : pou.actions) pouActions.push_back(a->name);
  std::optional<detail::ResolvedChart> resolved = detail::resolveChart(chart, pouActions, diags);
  if (!resolved || !detail::checkStepWrites(chart, pou, diags) || !detail::analyseChart(chart, *resolved, diags)) return;
  st::ChartSource source{copyOf(chart), {pou.body.size(), 0}, {pou.varBlocks.size(), 0}, {pou.actions.size(), 0}};
  Lowering(chart, *resolved, pou, nextNodeId).run();
  source.statements.end = pou.body.size();
  source.varBlocks.end = pou.varBlocks.size();
  source.actions.end = pou.actions.size();
  pou.chart = std::move(source);
}

}  // namespace virtcom::sfc
