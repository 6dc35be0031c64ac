#pragma once
// Deep copies of expressions and statements, for front-ends that keep a copy of what was written
// before lowering consumes it (lang/sfc keeps the chart as written).
#include "lang/syntax/ast.hpp"

namespace virtcom::st {

// A deep copy. With `nextNodeId` every node gets a fresh id (++*nextNodeId: a copy that is
// compiled must not share ids with the original); without it the ids are kept.
inline ExprPtr cloneExpr(const Expr& src, NodeId* nextNodeId = nullptr) {
  auto e = std::make_unique<Expr>();
  e->kind = src.kind;
  e->loc = src.loc;
  e->id = nextNodeId ? ++*nextNodeId : src.id;
  e->unaryOp = src.unaryOp;
  e->binaryOp = src.binaryOp;
  e->wide = src.wide;
  e->intValue = src.intValue;
  e->realValue = src.realValue;
  e->text = src.text;
  e->typePrefix = src.typePrefix;
  if (src.lhs) e->lhs = cloneExpr(*src.lhs, nextNodeId);
  if (src.rhs) e->rhs = cloneExpr(*src.rhs, nextNodeId);
  for (const auto& item : src.items) e->items.push_back(item ? cloneExpr(*item, nextNodeId) : nullptr);
  for (const auto& arg : src.args)
    e->args.push_back({arg.name, arg.output, arg.negated, arg.value ? cloneExpr(*arg.value, nextNodeId) : nullptr, arg.loc});
  return e;
}

inline ExprPtr cloneExprOrNull(const ExprPtr& src, NodeId* nextNodeId = nullptr) {
  return src ? cloneExpr(*src, nextNodeId) : nullptr;
}

inline StmtList cloneStatements(const StmtList& src, NodeId* nextNodeId = nullptr);

inline StmtPtr cloneStmt(const Stmt& src, NodeId* nextNodeId = nullptr) {
  auto s = std::make_unique<Stmt>();
  s->kind = src.kind;
  s->loc = src.loc;
  s->id = nextNodeId ? ++*nextNodeId : src.id;
  s->lhs = cloneExprOrNull(src.lhs, nextNodeId);
  s->rhs = cloneExprOrNull(src.rhs, nextNodeId);
  s->expr = cloneExprOrNull(src.expr, nextNodeId);
  s->to = cloneExprOrNull(src.to, nextNodeId);
  s->by = cloneExprOrNull(src.by, nextNodeId);
  for (const auto& b : src.branches)
    s->branches.push_back({cloneExprOrNull(b.cond, nextNodeId), cloneStatements(b.body, nextNodeId), b.loc});
  for (const auto& c : src.cases) {
    CaseBranch copy;
    for (const auto& label : c.labels)
      copy.labels.push_back({cloneExprOrNull(label.lo, nextNodeId), cloneExprOrNull(label.hi, nextNodeId)});
    copy.body = cloneStatements(c.body, nextNodeId);
    copy.loc = c.loc;
    s->cases.push_back(std::move(copy));
  }
  s->body = cloneStatements(src.body, nextNodeId);
  s->elseBody = cloneStatements(src.elseBody, nextNodeId);
  s->hasElse = src.hasElse;
  s->label = src.label;
  s->cover = src.cover;
  s->coverName = src.coverName;
  s->coverLoc = src.coverLoc;
  return s;
}

inline StmtList cloneStatements(const StmtList& src, NodeId* nextNodeId) {
  StmtList out;
  for (const auto& s : src) out.push_back(s ? cloneStmt(*s, nextNodeId) : nullptr);
  return out;
}

}  // namespace virtcom::st
