#pragma once
// Structured Text from the syntax tree: the inverse of the parser, up to layout, comments and
// redundant parentheses. Used to write ST bodies into exported PLCopen XML and as a normalised
// form of a program (parse -> print -> parse -> print is a fixed point).
#include <span>
#include <string>

#include "lang/syntax/ast.hpp"

namespace virtcom::st {

// One expression, with the parentheses operator precedence needs and no others.
std::string printExpr(const Expr& expr);

// Statements, one per line, nested bodies indented by one tab per level; `indent` is the level of
// the outermost statements. Every line ends with '\n'.
std::string printStatements(std::span<const StmtPtr> stmts, int indent = 0);

}  // namespace virtcom::st
