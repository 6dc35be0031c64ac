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

// A type as written in a declaration: `BOOL`, `ARRAY [1..3] OF INT`, `STRING(20)`, ...
std::string printType(const TypeSpec& type);

// A PROGRAM, FUNCTION_BLOCK or FUNCTION with its VAR blocks (attributes, AT locations, initial
// values), its ACTIONs (after the VAR blocks) and its body, ending in END_...; what the parser
// reads back into the same tree (pou_printer.cpp). Methods and properties are not written.
// Used by `virtcom ad export --st` for the lowered diagrams.
std::string printPou(const Pou& pou);

}  // namespace virtcom::st
