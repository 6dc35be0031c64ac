#include "lang/syntax/ast_builder.hpp"

namespace virtcom::st {

ExprPtr AstBuilder::expr(ExprKind kind) {
  auto e = std::make_unique<Expr>();
  e->kind = kind;
  e->loc = loc_;
  e->id = ++nextNodeId_;
  return e;
}

StmtPtr AstBuilder::stmt(StmtKind kind) {
  auto s = std::make_unique<Stmt>();
  s->kind = kind;
  s->loc = loc_;
  s->id = ++nextNodeId_;
  s->cover = role_;
  return s;
}

ExprPtr AstBuilder::name(std::string_view text) {
  ExprPtr e = expr(ExprKind::Name);
  e->text = text;
  return e;
}

ExprPtr AstBuilder::member(std::string_view base, std::string_view field) {
  ExprPtr e = expr(ExprKind::Member);
  e->lhs = name(base);
  e->text = field;
  return e;
}

ExprPtr AstBuilder::index(std::string_view array, uint64_t subscript) {
  ExprPtr e = expr(ExprKind::Index);
  e->lhs = name(array);
  e->items.push_back(intLit(subscript));
  return e;
}

ExprPtr AstBuilder::boolLit(bool value) {
  ExprPtr e = expr(ExprKind::BoolLit);
  e->intValue = value ? 1 : 0;
  return e;
}

ExprPtr AstBuilder::timeLit(int64_t ns) {
  ExprPtr e = expr(ExprKind::TimeLit);
  e->intValue = static_cast<uint64_t>(ns);
  e->typePrefix = "TIME";
  return e;
}

ExprPtr AstBuilder::intLit(uint64_t value) {
  ExprPtr e = expr(ExprKind::IntLit);
  e->intValue = value;
  return e;
}

ExprPtr AstBuilder::notOf(ExprPtr operand) {
  ExprPtr e = expr(ExprKind::Unary);
  e->unaryOp = UnaryOp::Not;
  e->lhs = std::move(operand);
  return e;
}

ExprPtr AstBuilder::binary(BinaryOp op, ExprPtr lhs, ExprPtr rhs) {
  ExprPtr e = expr(ExprKind::Binary);
  e->binaryOp = op;
  e->lhs = std::move(lhs);
  e->rhs = std::move(rhs);
  return e;
}

ExprPtr AstBuilder::orElseNull(ExprPtr lhs, ExprPtr rhs) {
  if (!lhs) return rhs;
  if (!rhs) return lhs;
  return binary(BinaryOp::Or, std::move(lhs), std::move(rhs));
}

ExprPtr AstBuilder::call(std::string_view callee, ExprPtr arg) {
  ExprPtr e = expr(ExprKind::Call);
  e->lhs = name(callee);
  if (arg) {
    CallArg a;
    a.value = std::move(arg);
    a.loc = loc_;
    e->args.push_back(std::move(a));
  }
  return e;
}

StmtPtr AstBuilder::assign(ExprPtr lhs, ExprPtr rhs) {
  StmtPtr s = stmt(StmtKind::Assign);
  s->lhs = std::move(lhs);
  s->rhs = std::move(rhs);
  return s;
}

StmtPtr AstBuilder::callStmt(std::string_view callee) {
  StmtPtr s = stmt(StmtKind::Call);
  s->expr = call(callee, nullptr);
  return s;
}

StmtPtr AstBuilder::callNamed(std::string_view callee, std::vector<std::pair<std::string, ExprPtr>> args) {
  StmtPtr s = stmt(StmtKind::Call);
  s->expr = call(callee, nullptr);
  for (auto& [argName, value] : args) {
    CallArg a;
    a.name = std::move(argName);
    a.value = std::move(value);
    a.loc = loc_;
    s->expr->args.push_back(std::move(a));
  }
  return s;
}

StmtPtr AstBuilder::ifThen(ExprPtr cond, StmtList body) {
  return ifThenElse(std::move(cond), std::move(body), {});
}

StmtPtr AstBuilder::ifThenElse(ExprPtr cond, StmtList body, StmtList elseBody) {
  StmtPtr s = stmt(StmtKind::If);
  CondBlock branch;
  branch.cond = std::move(cond);
  branch.body = std::move(body);
  branch.loc = loc_;
  s->branches.push_back(std::move(branch));
  s->hasElse = !elseBody.empty();
  s->elseBody = std::move(elseBody);
  return s;
}

StmtPtr AstBuilder::forLoop(std::string_view counter, uint64_t from, uint64_t to, StmtList body) {
  StmtPtr s = stmt(StmtKind::For);
  s->lhs = name(counter);
  s->rhs = intLit(from);
  s->to = intLit(to);
  s->body = std::move(body);
  return s;
}

StmtPtr AstBuilder::exitLoop() { return stmt(StmtKind::Exit); }

VarDecl AstBuilder::varDecl(std::string_view name, std::string_view typeName, bool hidden) {
  VarDecl decl;
  decl.names.push_back({std::string(name), loc_});
  decl.type.kind = TypeSpecKind::Named;
  decl.type.loc = loc_;
  decl.type.name = typeName;
  decl.loc = loc_;
  if (hidden) decl.attributes.push_back({"hide", ""});
  return decl;
}

VarDecl AstBuilder::arrayDecl(std::string_view name, std::string_view elementType, uint64_t count, bool hidden) {
  VarDecl decl = varDecl(name, "", hidden);
  decl.type.kind = TypeSpecKind::Array;
  decl.type.name.clear();
  decl.type.dims.push_back({intLit(1), intLit(count)});
  decl.type.element = std::make_unique<TypeSpec>();
  decl.type.element->loc = loc_;
  decl.type.element->name = elementType;
  return decl;
}

VarBlock AstBuilder::varBlock(VarSection section, std::vector<VarDecl> vars) {
  VarBlock block;
  block.section = section;
  block.vars = std::move(vars);
  block.loc = loc_;
  return block;
}

}  // namespace virtcom::st
