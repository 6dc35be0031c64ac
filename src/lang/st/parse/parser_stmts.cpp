// Statements: assignments, calls, IF, CASE, FOR, WHILE, REPEAT, EXIT, CONTINUE, RETURN, JMP, labels.
#include "core/ascii.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st::detail {

namespace {

// The construct a statement-level end keyword belongs to, for "no open IF" messages.
std::string_view openerOf(Tok end) {
  switch (end) {
    case Tok::KwEndIf: case Tok::KwElsif: return "IF";
    case Tok::KwElse: return "IF or CASE";
    case Tok::KwEndCase: return "CASE";
    case Tok::KwEndFor: return "FOR";
    case Tok::KwEndWhile: return "WHILE";
    default: return "REPEAT";
  }
}

bool contains(std::initializer_list<Tok> kinds, Tok kind) {
  for (Tok k : kinds)
    if (k == kind) return true;
  return false;
}

}  // namespace

bool Parser::isStatementStart(Tok kind) {
  switch (kind) {
    case Tok::KwIf: case Tok::KwCase: case Tok::KwFor: case Tok::KwWhile: case Tok::KwRepeat: case Tok::KwExit:
    case Tok::KwContinue: case Tok::KwReturn: case Tok::KwThis: case Tok::KwSuper: case Tok::Semicolon:
    case Tok::DirectAddress:
      return true;
    default:
      return isNameToken(kind);
  }
}

StmtList Parser::parseStatementList(std::initializer_list<Tok> ends, bool inCaseBranch) {
  StmtList list;
  while (!endsStatementList(ends, inCaseBranch)) {
    size_t before = pos_;
    if (StmtPtr stmt = parseStatement()) list.push_back(std::move(stmt));
    if (pos_ == before) advance();
  }
  return list;
}

// True at `ends`, at a declaration-level keyword, at an end keyword some enclosing construct is
// waiting for, or (in a CASE branch) at the next label. End keywords nobody waits for are
// reported and skipped.
bool Parser::endsStatementList(std::initializer_list<Tok> ends, bool inCaseBranch) {
  for (;;) {
    Tok kind = cur().kind;
    if (contains(ends, kind) || isHardStop(kind) || stopped_ || atSfcElement() || atSfcEnd()) return true;
    if (!isSoftEnd(kind)) return inCaseBranch && looksLikeCaseLabel();
    if (openEnds_[static_cast<size_t>(kind)] > 0) return true;
    error(diag::E006, "unexpected " + describe(cur()) + ": there is no open " + std::string(openerOf(kind)));
    advance();
  }
}

StmtPtr Parser::parseStatement() {
  NestingGuard guard(*this, kRecursionCost);
  if (!guard.ok) return nullptr;
  switch (cur().kind) {
    case Tok::KwIf: return parseIf();
    case Tok::KwCase: return parseCase();
    case Tok::KwFor: return parseFor();
    case Tok::KwWhile: return parseWhile();
    case Tok::KwRepeat: return parseRepeat();
    case Tok::KwExit: return parseSimple(StmtKind::Exit);
    case Tok::KwContinue: return parseSimple(StmtKind::Continue);
    case Tok::KwReturn: return parseSimple(StmtKind::Return);
    case Tok::Semicolon: {
      StmtPtr empty = makeStmt(StmtKind::Empty, cur().loc);
      advance();
      return empty;
    }
    default: break;
  }
  if (atLabel()) return parseLabel();
  if (atJump()) return parseJump();
  if (isStatementStart(cur().kind) || at(Tok::LParen)) return parseAssignmentOrCall();
  errorExpected("a statement", "");
  advance();
  skipPastSemicolon(true);
  return nullptr;
}

// CODESYS `x S= cond;` / `x R= cond;`: the lexer sees the name S or R followed by '='.
bool Parser::atSetResetOperator() const {
  const Token& tok = cur();
  const Token& next = peekTok(1);
  bool isSorR = tok.kind == Tok::Identifier && tok.text.size() == 1 &&
                (tok.text[0] == 'S' || tok.text[0] == 's' || tok.text[0] == 'R' || tok.text[0] == 'r');
  return isSorR && next.kind == Tok::Eq && next.loc.line == tok.loc.line && next.loc.col == tok.loc.col + 1;
}

StmtPtr Parser::parseAssignmentOrCall() {
  SourceLocation loc = cur().loc;
  ExprPtr target = parsePostfix();
  StmtKind kind = StmtKind::Assign;
  if (at(Tok::Assign)) {
    advance();
  } else if (at(Tok::RefAssignOp)) {
    kind = StmtKind::RefAssign;
    advance();
  } else if (at(Tok::AttemptAssignOp)) {
    kind = StmtKind::AttemptAssign;
    advance();
  } else if (atSetResetOperator()) {
    kind = (cur().text[0] == 'S' || cur().text[0] == 's') ? StmtKind::SetAssign : StmtKind::ResetAssign;
    advance();
    advance();
  } else if (target->kind == ExprKind::Call) {
    StmtPtr call = makeStmt(StmtKind::Call, loc);
    call->expr = std::move(target);
    expectStatementEnd();
    return call;
  } else {
    errorExpected("':=' or a call", "in statement");
    skipPastSemicolon(true);
    return nullptr;
  }
  StmtPtr stmt = makeStmt(kind, loc);
  stmt->lhs = std::move(target);
  stmt->rhs = parseExpr();
  expectStatementEnd();
  return stmt;
}

// A missing ';' at the end of a line is reported and assumed; anything else on the same line is
// skipped up to the next ';'.
void Parser::expectStatementEnd() {
  if (accept(Tok::Semicolon)) return;
  errorExpected("';'", "after statement");
  bool onNewLine = pos_ > 0 && cur().loc.line > toks_[pos_ - 1].loc.line;
  if (!onNewLine) skipPastSemicolon(true);
}

// `name :` (not `:=`) at the start of a statement is a jump label (CODESYS). In a CASE branch
// the parser has already taken `name :` as the next case label.
bool Parser::atLabel() const { return isNameToken(cur().kind) && peekTok(1).kind == Tok::Colon; }

StmtPtr Parser::parseLabel() {
  StmtPtr label = makeStmt(StmtKind::Label, cur().loc);
  label->label = cur().text;
  advance();
  advance();
  return label;
}

// JMP is no reserved word: `JMP name` (two names in a row) is a jump, `jmp := 1;` an assignment.
bool Parser::atJump() const {
  return cur().kind == Tok::Identifier && iequalsAscii(cur().text, "JMP") && isNameToken(peekTok(1).kind);
}

StmtPtr Parser::parseJump() {
  StmtPtr jump = makeStmt(StmtKind::Jump, cur().loc);
  advance();
  jump->label = cur().text;
  advance();
  expectStatementEnd();
  return jump;
}

StmtPtr Parser::parseSimple(StmtKind kind) {
  StmtPtr stmt = makeStmt(kind, cur().loc);
  advance();
  expectStatementEnd();
  return stmt;
}

StmtPtr Parser::parseIf() {
  SourceLocation loc = cur().loc;
  OpenConstruct open(*this, {Tok::KwElsif, Tok::KwElse, Tok::KwEndIf});
  StmtPtr stmt = makeStmt(StmtKind::If, loc);
  do {
    CondBlock branch;
    branch.loc = cur().loc;
    bool isElsif = at(Tok::KwElsif);
    advance();
    branch.cond = parseExpr();
    expect(Tok::KwThen, isElsif ? "after ELSIF condition" : "after IF condition");
    branch.body = parseStatementList({Tok::KwElsif, Tok::KwElse, Tok::KwEndIf});
    stmt->branches.push_back(std::move(branch));
  } while (!stopped_ && at(Tok::KwElsif));
  if (accept(Tok::KwElse)) {
    stmt->hasElse = true;
    stmt->elseBody = parseStatementList({Tok::KwEndIf});
  }
  expectEnd(Tok::KwEndIf, "IF", loc);
  return stmt;
}

StmtPtr Parser::parseCase() {
  SourceLocation loc = cur().loc;
  OpenConstruct open(*this, {Tok::KwElse, Tok::KwEndCase});
  StmtPtr stmt = makeStmt(StmtKind::Case, loc);
  advance();
  stmt->expr = parseExpr();
  expect(Tok::KwOf, "after CASE selector");
  while (!endsStatementList({Tok::KwElse, Tok::KwEndCase}, false)) {
    size_t before = pos_;
    CaseBranch branch;
    if (parseCaseBranch(branch)) stmt->cases.push_back(std::move(branch));
    if (pos_ == before) advance();
  }
  if (accept(Tok::KwElse)) {
    accept(Tok::Colon);  // some code writes `ELSE:`
    stmt->hasElse = true;
    stmt->elseBody = parseStatementList({Tok::KwEndCase});
  }
  expectEnd(Tok::KwEndCase, "CASE", loc);
  return stmt;
}

// `1, 2, 5..7, Color.Red:` followed by the branch's statements.
bool Parser::parseCaseBranch(CaseBranch& branch) {
  branch.loc = cur().loc;
  do {
    CaseLabel label;
    label.lo = parseExpr();
    if (accept(Tok::DotDot)) label.hi = parseExpr();
    branch.labels.push_back(std::move(label));
  } while (!stopped_ && accept(Tok::Comma));
  if (!expect(Tok::Colon, "after CASE label")) {
    skipPastSemicolon(true);
    return false;
  }
  branch.body = parseStatementList({Tok::KwElse, Tok::KwEndCase}, true);
  return true;
}

// Decides whether the tokens ahead form `labels :` (a new CASE branch) rather than a statement:
// a label list holds only constants, names, '.', '..', ',', signs, arithmetic and parentheses,
// and ends at a ':' that is not ':='.
bool Parser::looksLikeCaseLabel() const {
  constexpr size_t kMaxLookahead = 256;
  int parens = 0;
  for (size_t i = 0; i < kMaxLookahead; ++i) {
    Tok kind = peekTok(i).kind;
    switch (kind) {
      case Tok::Colon: return i > 0 && parens == 0;
      case Tok::LParen: ++parens; break;
      case Tok::RParen:
        if (--parens < 0) return false;
        break;
      case Tok::IntLiteral: case Tok::RealLiteral: case Tok::StringLiteral: case Tok::WStringLiteral:
      case Tok::TypedPrefix: case Tok::TimeLiteral: case Tok::DateLiteral: case Tok::KwTrue: case Tok::KwFalse:
      case Tok::Dot: case Tok::DotDot: case Tok::Comma: case Tok::Plus: case Tok::Minus: case Tok::Star:
      case Tok::Slash: case Tok::KwMod:
        break;
      default:
        if (!isNameToken(kind)) return false;
        break;
    }
  }
  return false;
}

StmtPtr Parser::parseFor() {
  SourceLocation loc = cur().loc;
  OpenConstruct open(*this, {Tok::KwEndFor});
  StmtPtr stmt = makeStmt(StmtKind::For, loc);
  advance();
  stmt->lhs = parsePostfix();
  expect(Tok::Assign, "after FOR control variable");
  stmt->rhs = parseExpr();
  expect(Tok::KwTo, "after FOR start value");
  stmt->to = parseExpr();
  if (accept(Tok::KwBy)) stmt->by = parseExpr();
  expect(Tok::KwDo, "after FOR range");
  stmt->body = parseStatementList({Tok::KwEndFor});
  expectEnd(Tok::KwEndFor, "FOR", loc);
  return stmt;
}

StmtPtr Parser::parseWhile() {
  SourceLocation loc = cur().loc;
  OpenConstruct open(*this, {Tok::KwEndWhile});
  StmtPtr stmt = makeStmt(StmtKind::While, loc);
  advance();
  stmt->expr = parseExpr();
  expect(Tok::KwDo, "after WHILE condition");
  stmt->body = parseStatementList({Tok::KwEndWhile});
  expectEnd(Tok::KwEndWhile, "WHILE", loc);
  return stmt;
}

StmtPtr Parser::parseRepeat() {
  SourceLocation loc = cur().loc;
  OpenConstruct open(*this, {Tok::KwUntil, Tok::KwEndRepeat});
  StmtPtr stmt = makeStmt(StmtKind::Repeat, loc);
  advance();
  stmt->body = parseStatementList({Tok::KwUntil});
  expect(Tok::KwUntil, "at the end of REPEAT");
  stmt->expr = parseExpr();
  expectEnd(Tok::KwEndRepeat, "REPEAT", loc);
  return stmt;
}

}  // namespace virtcom::st::detail
