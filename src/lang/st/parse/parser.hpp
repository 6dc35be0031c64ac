#pragma once
// The Structured Text parser: source text to the syntax tree of ast.hpp.
#include <cstdint>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::st {

// Parses one file (lexing it first). Never throws and never crashes, whatever the input: syntax
// errors become diagnostics (codes E001-E013) and parsing resumes at the next ';', END_xxx or
// declaration keyword, so one run reports many errors; the returned unit holds everything that
// could be parsed. `nextNodeId` is a counter shared by the files of one compilation: every Expr
// and Stmt gets a unique id (++nextNodeId). GlobalVarList::name is left empty (the caller knows
// the file name). Nesting deeper than an internal bound (about 256 levels) is reported as E010
// and ends the parse of that file.
//
// Conventions of the produced tree:
// - Literals hold magnitudes; a sign is a Unary Neg around the literal: `-5`, `INT#-5` and
//   `T#-5s` all become Neg(literal), with the type prefix on the literal.
// - TimeLit.intValue is nanoseconds for TIME and LTIME alike; DateLit is seconds since 1970
//   (DATE, DT; DT fractions of a second are dropped) or ms since midnight (TOD).
// - Typed literals carry the canonical type name in typePrefix ("INT", "TIME_OF_DAY" is "TOD").
//   BOOL#0/1 is a BoolLit, REAL#1 a RealLit.
// - POINTER TO T and IEC REF_TO T give a Pointer spec; CODESYS REFERENCE TO T a Reference.
// - ARRAY[*] dimensions have null bounds; UNION and VAR_CONFIG are reported as unsupported (E011).
// - Pou::body holds, in source order, the statements before, between and after the POU's
//   METHOD, PROPERTY and ACTION blocks (TwinCAT/CODESYS exports put those before the body).
// - The operators in function form, `MOD(a, b)`, `AND(a, b, c)`, `OR(...)`, `XOR(...)`, are Calls
//   whose callee is a Name with the upper-case spelling ("MOD"); so is `NOT(...)` with named or
//   several arguments, while `NOT(x)` / `NOT (a OR b)` stay a Unary Not.
// - Textual SFC (INITIAL_STEP, STEP, TRANSITION) in a PROGRAM or FUNCTION_BLOCK body is lowered
//   into ordinary variables and statements of that POU (lang/sfc/lower.hpp); chart errors are
//   E401-E408.
// - Parentheses leave no node. A syntax error inside an expression leaves a Name node with an
//   empty text in its place.
// - Binary, Unary, Index and Deref nodes are located at their operator; Member and BitAccess at
//   the member name; Call at its callee; statements at their first token; POUs, methods,
//   properties, types and variables at their name.
CompilationUnit parseFile(uint32_t fileId, std::string_view text, Diagnostics& diags, NodeId& nextNodeId);

// Fragments of a larger file (ST embedded in PLCopen XML), lexed with lexFragment() so every
// location points into file `fileId` from `origin` on; same guarantees as parseFile().
// parseStatements: a statement list (a POU body); anything else is reported (E006) and skipped.
// parseExpression: exactly one expression; never null (a syntax error leaves an empty Name).
StmtList parseStatements(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags,
                         NodeId& nextNodeId);
ExprPtr parseExpression(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags,
                        NodeId& nextNodeId);

}  // namespace virtcom::st
