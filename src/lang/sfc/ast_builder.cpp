#include "lang/sfc/ast_builder.hpp"

namespace virtcom::sfc::detail {

st::ExprPtr AstBuilder::expr(st::ExprKind kind) {
  auto e = std::make_unique<st::Expr>();
  e->kind = kind;
  e->loc = loc_;
  e->id = ++nextNodeId_;
  return e;
}

st::StmtPtr AstBuilder::stmt(st::StmtKind kind) {
  auto s = std::make_unique<st::Stmt>();
  s->kind = kind;
  s->loc = loc_;
  s->id = ++nextNodeId_;
  return s;
}

st::ExprPtr AstBuilder::name(std::string_view text) {
  st::ExprPtr e = expr(st::ExprKind::Name);
  e->text = text;
  return e;
}

st::ExprPtr AstBuilder::member(std::string_view base, std::string_view field) {
  st::ExprPtr e = expr(st::ExprKind::Member);
  e->lhs = name(base);
  e->text = field;
  return e;
}

st::ExprPtr AstBuilder::boolLit(bool value) {
  st::ExprPtr e = expr(st::ExprKind::BoolLit);
  e->intValue = value ? 1 : 0;
  return e;
}

st::ExprPtr AstBuilder::timeLit(int64_t ns) {
  st::ExprPtr e = expr(st::ExprKind::TimeLit);
  e->intValue = static_cast<uint64_t>(ns);
  e->typePrefix = "TIME";
  return e;
}

st::ExprPtr AstBuilder::intLit(uint64_t value) {
  st::ExprPtr e = expr(st::ExprKind::IntLit);
  e->intValue = value;
  return e;
}

st::ExprPtr AstBuilder::notOf(st::ExprPtr operand) {
  st::ExprPtr e = expr(st::ExprKind::Unary);
  e->unaryOp = st::UnaryOp::Not;
  e->lhs = std::move(operand);
  return e;
}

st::ExprPtr AstBuilder::binary(st::BinaryOp op, st::ExprPtr lhs, st::ExprPtr rhs) {
  st::ExprPtr e = expr(st::ExprKind::Binary);
  e->binaryOp = op;
  e->lhs = std::move(lhs);
  e->rhs = std::move(rhs);
  return e;
}

st::ExprPtr AstBuilder::orElseNull(st::ExprPtr lhs, st::ExprPtr rhs) {
  if (!lhs) return rhs;
  if (!rhs) return lhs;
  return binary(st::BinaryOp::Or, std::move(lhs), std::move(rhs));
}

st::ExprPtr AstBuilder::call(std::string_view callee, st::ExprPtr arg) {
  st::ExprPtr e = expr(st::ExprKind::Call);
  e->lhs = name(callee);
  if (arg) {
    st::CallArg a;
    a.value = std::move(arg);
    a.loc = loc_;
    e->args.push_back(std::move(a));
  }
  return e;
}

st::StmtPtr AstBuilder::assign(st::ExprPtr lhs, st::ExprPtr rhs) {
  st::StmtPtr s = stmt(st::StmtKind::Assign);
  s->lhs = std::move(lhs);
  s->rhs = std::move(rhs);
  return s;
}

st::StmtPtr AstBuilder::callStmt(std::string_view callee) {
  st::StmtPtr s = stmt(st::StmtKind::Call);
  s->expr = call(callee, nullptr);
  return s;
}

st::StmtPtr AstBuilder::ifThen(st::ExprPtr cond, st::StmtList body) {
  return ifThenElse(std::move(cond), std::move(body), {});
}

st::StmtPtr AstBuilder::ifThenElse(st::ExprPtr cond, st::StmtList body, st::StmtList elseBody) {
  st::StmtPtr s = stmt(st::StmtKind::If);
  st::CondBlock branch;
  branch.cond = std::move(cond);
  branch.body = std::move(body);
  branch.loc = loc_;
  s->branches.push_back(std::move(branch));
  s->hasElse = !elseBody.empty();
  s->elseBody = std::move(elseBody);
  return s;
}

st::StmtPtr AstBuilder::forLoop(std::string_view counter, uint64_t from, uint64_t to, st::StmtList body) {
  st::StmtPtr s = stmt(st::StmtKind::For);
  s->lhs = name(counter);
  s->rhs = intLit(from);
  s->to = intLit(to);
  s->body = std::move(body);
  return s;
}

st::StmtPtr AstBuilder::exitLoop() { return stmt(st::StmtKind::Exit); }

st::VarDecl AstBuilder::varDecl(std::string_view name, std::string_view typeName, bool hidden) {
  st::VarDecl decl;
  decl.names.push_back({std::string(name), loc_});
  decl.type.kind = st::TypeSpecKind::Named;
  decl.type.loc = loc_;
  decl.type.name = typeName;
  decl.loc = loc_;
  if (hidden) decl.attributes.push_back({"hide", ""});
  return decl;
}

}  // namespace virtcom::sfc::detail
