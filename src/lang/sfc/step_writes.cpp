// E409: the chart alone sets its step flags. An assignment to `Step.X` / `Step.T` in the POU
// (its statements, ACTIONs, METHODs, transition bodies, chart actions) would break the
// evolution, so it is rejected before the chart is lowered (the lowering's own writes are not
// user code and never pass through here).
#include <set>

#include "lang/sfc/chart_check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::sfc::detail {

namespace {

class StepWriteCheck {
 public:
  StepWriteCheck(const Chart& chart, Diagnostics& diags) : diags_(diags) {
    for (const Step& s : chart.steps) steps_.insert(nameKey(s.name));
  }

  void statements(const st::StmtList& list) {
    for (const auto& s : list)
      if (s) statement(*s);
  }
  bool ok() const { return ok_; }

 private:
  void statement(const st::Stmt& s) {
    switch (s.kind) {
      case st::StmtKind::Assign: case st::StmtKind::RefAssign: case st::StmtKind::AttemptAssign:
      case st::StmtKind::SetAssign: case st::StmtKind::ResetAssign: case st::StmtKind::For:
        target(s.lhs.get());
        break;
      default: break;
    }
    for (const st::Expr* e : {s.rhs.get(), s.expr.get(), s.to.get(), s.by.get()}) outputs(e);
    for (const auto& b : s.branches) {
      outputs(b.cond.get());
      statements(b.body);
    }
    for (const auto& c : s.cases) statements(c.body);
    statements(s.body);
    statements(s.elseBody);
  }

  // Output arguments of calls (`fb(Q => Step.X)`) write too.
  void outputs(const st::Expr* e) {
    if (!e) return;
    for (const auto& arg : e->args) {
      if (arg.output) target(arg.value.get());
      else outputs(arg.value.get());
    }
    outputs(e->lhs.get());
    outputs(e->rhs.get());
    for (const auto& item : e->items) outputs(item.get());
  }

  void target(const st::Expr* e) {
    if (!e || e->kind != st::ExprKind::Member || !e->lhs || e->lhs->kind != st::ExprKind::Name) return;
    std::string field = nameKey(e->text);
    if ((field != "X" && field != "T") || !steps_.count(nameKey(e->lhs->text))) return;
    diags_.error(st::diag::E409, e->lhs->loc, "'" + e->lhs->text + "." + e->text + "' is a step flag, which only the chart sets; "
                                         "set a BOOL variable in an action of the step instead");
    ok_ = false;
  }

  Diagnostics& diags_;
  std::set<std::string> steps_;
  bool ok_ = true;
};

}  // namespace

bool checkStepWrites(const Chart& chart, const st::Pou& pou, Diagnostics& diags) {
  StepWriteCheck check(chart, diags);
  check.statements(pou.body);
  for (const auto* list : {&pou.actions, &pou.methods})
    for (const auto& p : *list) check.statements(p->body);
  for (const Transition& t : chart.transitions) check.statements(t.body);
  for (const Action& a : chart.actions) check.statements(a.body);
  return check.ok();
}

}  // namespace virtcom::sfc::detail
