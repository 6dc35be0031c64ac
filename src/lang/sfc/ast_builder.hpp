#pragma once
// Internal to lang/sfc: builds the ST nodes of a lowered chart. Every node gets a fresh id
// (++nextNodeId) and the location set by at(), so errors in generated code point at the chart
// element it came from.
#include <string_view>

#include "lang/syntax/ast.hpp"

namespace virtcom::sfc::detail {

class AstBuilder {
 public:
  explicit AstBuilder(st::NodeId& nextNodeId) : nextNodeId_(nextNodeId) {}
  void at(SourceLocation loc) { loc_ = loc; }

  st::ExprPtr name(std::string_view text);
  st::ExprPtr member(std::string_view base, std::string_view field);  // base.field
  st::ExprPtr boolLit(bool value);
  st::ExprPtr timeLit(int64_t ns);
  st::ExprPtr intLit(uint64_t value);
  st::ExprPtr notOf(st::ExprPtr operand);
  st::ExprPtr binary(st::BinaryOp op, st::ExprPtr lhs, st::ExprPtr rhs);
  // lhs OR rhs, where a null side is "no term" (so terms can be collected one by one).
  st::ExprPtr orElseNull(st::ExprPtr lhs, st::ExprPtr rhs);
  st::ExprPtr call(std::string_view callee, st::ExprPtr arg);  // callee(arg); arg may be null

  st::StmtPtr assign(st::ExprPtr lhs, st::ExprPtr rhs);
  st::StmtPtr callStmt(std::string_view callee);  // callee();
  st::StmtPtr ifThen(st::ExprPtr cond, st::StmtList body);
  st::StmtPtr ifThenElse(st::ExprPtr cond, st::StmtList body, st::StmtList elseBody);
  // FOR counter := from TO to DO body END_FOR
  st::StmtPtr forLoop(std::string_view counter, uint64_t from, uint64_t to, st::StmtList body);
  st::StmtPtr exitLoop();

  // A variable declaration `name : typeName` with optional {attribute 'hide'}.
  st::VarDecl varDecl(std::string_view name, std::string_view typeName, bool hidden);

 private:
  st::ExprPtr expr(st::ExprKind kind);
  st::StmtPtr stmt(st::StmtKind kind);

  st::NodeId& nextNodeId_;
  SourceLocation loc_;
};

}  // namespace virtcom::sfc::detail
