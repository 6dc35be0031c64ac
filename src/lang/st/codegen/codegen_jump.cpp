// Code generation: JMP and labels (CODESYS `label:` ... `JMP label;`). A label is visible in its
// own statement list and in every list nested in it, so a jump goes forward or backward in its
// list or out of IF, CASE and loops, but never into one (E220): that would skip the code that
// starts a FOR (its end value) or the test that guards a branch. Labels are names, compared
// without case as every IEC name, and unique in a body (E219).
#include "core/ascii.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

void forEachLabel(const StmtList& list, const auto& visit) {
  for (const auto& s : list) {
    if (s->kind == StmtKind::Label) visit(*s);
    for (const auto& b : s->branches) forEachLabel(b.body, visit);
    for (const auto& c : s->cases) forEachLabel(c.body, visit);
    forEachLabel(s->body, visit);
    forEachLabel(s->elseBody, visit);
  }
}

std::string position(const Stmt& label) {
  return "line " + std::to_string(label.loc.line) + ", col " + std::to_string(label.loc.col);
}

}  // namespace

void PouCompiler::collectLabels(const StmtList& list) {
  forEachLabel(list, [&](const Stmt& label) {
    for (const Stmt* seen : bodyLabels_)
      if (iequalsAscii(seen->label, label.label)) {
        diags().error(diag::E219, label.loc, "the label '" + label.label + "' is already defined at " + position(*seen) +
                                                 "; each label of a body needs its own name");
        return;
      }
    bodyLabels_.push_back(&label);
  });
}

// The labels written directly in `list`, if it has any (a duplicate keeps the first).
bool PouCompiler::openLabelScope(const StmtList& list) {
  LabelScope scope;
  for (const auto& s : list)
    if (s->kind == StmtKind::Label) scope.push_back({s.get(), std::nullopt, {}});
  if (scope.empty()) return false;
  labelScopes_.push_back(std::move(scope));
  return true;
}

// Every label of the list was reached on the way, so no jump is left waiting.
void PouCompiler::closeLabelScope() { labelScopes_.pop_back(); }

void PouCompiler::placeLabel(const Stmt& s) {
  for (JumpLabel& label : labelScopes_.back()) {
    if (label.stmt != &s) continue;
    label.target = here();
    for (uint32_t j : label.pending) patchJump(j, *label.target);
    label.pending.clear();
  }
}

void PouCompiler::jump(const Stmt& s) {
  for (auto scope = labelScopes_.rbegin(); scope != labelScopes_.rend(); ++scope)
    for (JumpLabel& label : *scope) {
      if (!iequalsAscii(label.stmt->label, s.label)) continue;
      if (label.target) jumpTo(bc::Op::JMP, 0, *label.target);
      else label.pending.push_back(emitJump(bc::Op::JMP, 0));
      return;
    }
  for (const Stmt* label : bodyLabels_)
    if (iequalsAscii(label->label, s.label)) {
      diags().error(diag::E220, s.loc, "JMP " + s.label + " would jump into the statement that holds the label (" +
                                           position(*label) + "); a jump may only go to a label in its own statement list or an enclosing one");
      return;
    }
  diags().error(diag::E219, s.loc, "there is no label '" + s.label + "' in this body; expected a label written '" +
                                       s.label + ":' before a statement of the same POU body");
}

}  // namespace virtcom::st
