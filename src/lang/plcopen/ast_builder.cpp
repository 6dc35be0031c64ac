#include "lang/plcopen/ast_builder.hpp"

#include "lang/syntax/ast_clone.hpp"

namespace virtcom::plcopen {

st::ExprPtr AstBuilder::expr(st::ExprKind kind, SourceLocation loc) {
  auto e = std::make_unique<st::Expr>();
  e->kind = kind;
  e->loc = loc;
  e->id = ++nextNodeId_;
  return e;
}

st::StmtPtr AstBuilder::makeStmt(st::StmtKind kind, SourceLocation loc) {
  auto s = std::make_unique<st::Stmt>();
  s->kind = kind;
  s->loc = loc;
  s->id = ++nextNodeId_;
  return s;
}

st::ExprPtr AstBuilder::name(std::string text, SourceLocation loc) {
  auto e = expr(st::ExprKind::Name, loc);
  e->text = std::move(text);
  return e;
}

st::ExprPtr AstBuilder::boolLit(bool value, SourceLocation loc) {
  auto e = expr(st::ExprKind::BoolLit, loc);
  e->intValue = value ? 1 : 0;
  return e;
}

st::ExprPtr AstBuilder::intLit(uint64_t value, SourceLocation loc) {
  auto e = expr(st::ExprKind::IntLit, loc);
  e->intValue = value;
  return e;
}

st::ExprPtr AstBuilder::member(st::ExprPtr base, std::string field, SourceLocation loc) {
  auto e = expr(st::ExprKind::Member, loc);
  e->lhs = std::move(base);
  e->text = std::move(field);
  return e;
}

st::ExprPtr AstBuilder::notOf(st::ExprPtr operand) {
  auto e = expr(st::ExprKind::Unary, operand->loc);
  e->unaryOp = st::UnaryOp::Not;
  e->lhs = std::move(operand);
  return e;
}

st::ExprPtr AstBuilder::binary(st::BinaryOp op, st::ExprPtr lhs, st::ExprPtr rhs) {
  auto e = expr(st::ExprKind::Binary, lhs->loc);
  e->binaryOp = op;
  e->lhs = std::move(lhs);
  e->rhs = std::move(rhs);
  return e;
}

st::ExprPtr AstBuilder::clone(const st::Expr& src) { return st::cloneExpr(src, &nextNodeId_); }

st::StmtPtr AstBuilder::assign(st::ExprPtr lhs, st::ExprPtr rhs, st::StmtKind kind) {
  auto s = makeStmt(kind, lhs->loc);
  s->lhs = std::move(lhs);
  s->rhs = std::move(rhs);
  return s;
}

st::StmtPtr AstBuilder::callStmt(st::ExprPtr call) {
  auto s = makeStmt(st::StmtKind::Call, call->loc);
  s->expr = std::move(call);
  return s;
}

st::StmtPtr AstBuilder::ifThen(st::ExprPtr cond, st::StmtList body) {
  auto s = makeStmt(st::StmtKind::If, cond->loc);
  st::CondBlock branch;
  branch.loc = cond->loc;
  branch.cond = std::move(cond);
  branch.body = std::move(body);
  s->branches.push_back(std::move(branch));
  return s;
}

st::StmtPtr AstBuilder::simple(st::StmtKind kind, SourceLocation loc) { return makeStmt(kind, loc); }

st::StmtPtr AstBuilder::whileLoop(st::ExprPtr cond, st::StmtList body) {
  auto s = makeStmt(st::StmtKind::While, cond->loc);
  s->expr = std::move(cond);
  s->body = std::move(body);
  return s;
}

}  // namespace virtcom::plcopen
