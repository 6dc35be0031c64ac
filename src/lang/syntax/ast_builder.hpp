#pragma once
// Builds syntax-tree nodes for front-ends that lower a model to ST (lang/sfc charts, lang/ad
// activity diagrams). Every node gets a fresh id (++nextNodeId) and the location set by at(), so
// errors in generated code point at the model element it came from.
#include <string_view>
#include <utility>
#include <vector>

#include "lang/syntax/ast.hpp"

namespace virtcom::st {

class AstBuilder {
 public:
  explicit AstBuilder(NodeId& nextNodeId) : nextNodeId_(nextNodeId) {}
  void at(SourceLocation loc) { loc_ = loc; }
  // Statements built from now on are bookkeeping of a lowering, not code the user wrote: code
  // coverage does not count them by line (CoverRole::Generated).
  void generated(bool on) { role_ = on ? CoverRole::Generated : CoverRole::Source; }

  ExprPtr name(std::string_view text);
  ExprPtr member(std::string_view base, std::string_view field);  // base.field
  ExprPtr index(std::string_view array, uint64_t subscript);       // array[subscript]
  ExprPtr boolLit(bool value);
  ExprPtr timeLit(int64_t ns);
  ExprPtr intLit(uint64_t value);
  ExprPtr notOf(ExprPtr operand);
  ExprPtr binary(BinaryOp op, ExprPtr lhs, ExprPtr rhs);
  // lhs OR rhs, where a null side is "no term" (so terms can be collected one by one).
  ExprPtr orElseNull(ExprPtr lhs, ExprPtr rhs);
  ExprPtr call(std::string_view callee, ExprPtr arg);  // callee(arg); arg may be null

  StmtPtr assign(ExprPtr lhs, ExprPtr rhs);
  StmtPtr callStmt(std::string_view callee);  // callee();
  // callee(name1 := value1, ...); a function block instance call with named inputs.
  StmtPtr callNamed(std::string_view callee, std::vector<std::pair<std::string, ExprPtr>> args);
  StmtPtr ifThen(ExprPtr cond, StmtList body);
  StmtPtr ifThenElse(ExprPtr cond, StmtList body, StmtList elseBody);
  // FOR counter := from TO to DO body END_FOR
  StmtPtr forLoop(std::string_view counter, uint64_t from, uint64_t to, StmtList body);
  StmtPtr exitLoop();

  // A variable declaration `name : typeName` with optional {attribute 'hide'}.
  VarDecl varDecl(std::string_view name, std::string_view typeName, bool hidden);
  // `name : ARRAY [1..count] OF elementType` with optional {attribute 'hide'}.
  VarDecl arrayDecl(std::string_view name, std::string_view elementType, uint64_t count, bool hidden);
  // A VAR_... block of the given section holding `vars`.
  VarBlock varBlock(VarSection section, std::vector<VarDecl> vars);

 private:
  ExprPtr expr(ExprKind kind);
  StmtPtr stmt(StmtKind kind);

  NodeId& nextNodeId_;
  SourceLocation loc_;
  CoverRole role_ = CoverRole::Source;
};

}  // namespace virtcom::st
