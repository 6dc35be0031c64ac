#pragma once
// Makes the ST syntax-tree nodes the importer needs, each with a fresh node id and a location in
// the XML file, so the checker and code generator treat them exactly like parsed ST.
#include <string>

#include "lang/syntax/ast.hpp"

namespace virtcom::plcopen {

class AstBuilder {
 public:
  explicit AstBuilder(st::NodeId& nextNodeId) : nextNodeId_(nextNodeId) {}

  st::ExprPtr expr(st::ExprKind kind, SourceLocation loc);  // an empty node of that kind
  st::ExprPtr name(std::string text, SourceLocation loc);
  st::ExprPtr boolLit(bool value, SourceLocation loc);
  st::ExprPtr intLit(uint64_t value, SourceLocation loc);
  st::ExprPtr member(st::ExprPtr base, std::string field, SourceLocation loc);
  st::ExprPtr notOf(st::ExprPtr operand);
  st::ExprPtr binary(st::BinaryOp op, st::ExprPtr lhs, st::ExprPtr rhs);
  // A deep copy with fresh node ids (an expression used in two places must be two nodes).
  st::ExprPtr clone(const st::Expr& expr);

  st::StmtPtr assign(st::ExprPtr lhs, st::ExprPtr rhs, st::StmtKind kind = st::StmtKind::Assign);
  st::StmtPtr callStmt(st::ExprPtr call);
  st::StmtPtr ifThen(st::ExprPtr cond, st::StmtList body);
  st::StmtPtr simple(st::StmtKind kind, SourceLocation loc);  // RETURN, EXIT, CONTINUE
  st::StmtPtr whileLoop(st::ExprPtr cond, st::StmtList body);

 private:
  st::StmtPtr makeStmt(st::StmtKind kind, SourceLocation loc);
  st::NodeId& nextNodeId_;
};

}  // namespace virtcom::plcopen
