// Textual SFC (IEC 61131-3) inside a PROGRAM or FUNCTION_BLOCK body:
//   INITIAL_STEP name : association; ... END_STEP      STEP name : ... END_STEP
//   association ::= action ( [qualifier [, duration] [, indicator]] ) ;
//   TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps (:= condition ; | : statements)
//   END_TRANSITION                                   steps ::= name | ( name {, name} )
// ACTION ... END_ACTION blocks are the POU's ordinary ACTIONs (parser_pous.cpp).
#include "core/ascii.hpp"
#include "lang/sfc/lower.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st::detail {

namespace {

// `word` is upper case; SFC keywords are identifiers to the lexer.
bool isWord(const Token& tok, std::string_view word) { return tok.kind == Tok::Identifier && iequalsAscii(tok.text, word); }

}  // namespace

bool Parser::atSfcElement() const {
  const Token& tok = cur();
  if (tok.kind != Tok::Identifier) return false;
  if (isWord(tok, "INITIAL_STEP")) return isNameToken(peekTok(1).kind);
  if (isWord(tok, "STEP")) return isNameToken(peekTok(1).kind) && peekTok(2).kind == Tok::Colon;
  if (!isWord(tok, "TRANSITION")) return false;
  const Token& next = peekTok(1);
  if (isWord(next, "FROM")) return true;
  if (next.kind == Tok::LParen) return isWord(peekTok(2), "PRIORITY");
  return isNameToken(next.kind) && (isWord(peekTok(2), "FROM") || peekTok(2).kind == Tok::LParen);
}

bool Parser::atSfcEnd() const {
  return (isWord(cur(), "END_STEP") || isWord(cur(), "END_TRANSITION")) && peekTok(1).kind != Tok::Assign;
}

void Parser::parseSfcElement(sfc::Chart& chart) {
  if (chart.empty()) chart.loc = cur().loc;
  if (isWord(cur(), "TRANSITION")) {
    chart.transitions.push_back(parseTransition());
  } else {
    chart.steps.push_back(parseStep());
  }
}

sfc::Step Parser::parseStep() {
  sfc::Step step;
  step.initial = isWord(cur(), "INITIAL_STEP");
  std::string_view opener = step.initial ? "INITIAL_STEP" : "STEP";
  SourceLocation keywordLoc = cur().loc;
  advance();
  step.name = expectName("a step name", &step.loc);
  expect(Tok::Colon, "after the step name");
  size_t lastStray = kNoStray;
  while (!stopped_ && !atSfcEnd() && !atSfcElement() && !isHardStop(cur().kind)) {
    if (!atName()) {
      skipStray(lastStray, "an action association such as A(N); or END_STEP");
    } else if (!parseActionAssociation(step)) {
      skipPastSemicolon(true);
    }
  }
  if (isWord(cur(), "END_STEP")) {
    advance();
    accept(Tok::Semicolon);
  } else {
    error(diag::E007, "expected 'END_STEP' to close '" + std::string(opener) + "' at line " +
                          std::to_string(keywordLoc.line) + ", found " + describe(cur()));
  }
  return step;
}

// action ( [qualifier [, duration] [, indicator]] ) ;   -- `A();` and `A;` mean N
bool Parser::parseActionAssociation(sfc::Step& step) {
  sfc::ActionAssociation a;
  a.action.name = expectName("an action name", &a.action.loc);
  a.loc = a.action.loc;
  if (accept(Tok::LParen) && !accept(Tok::RParen)) {
    a.loc = cur().loc;
    std::optional<sfc::Qualifier> q = atName() ? sfc::qualifierFromText(cur().text) : std::nullopt;
    if (!q) {
      error(diag::E404, "expected an action qualifier (N, R, S, L, D, P, P0, P1, SD, DS or SL), found " + describe(cur()));
      return false;
    }
    a.qualifier = *q;
    advance();
    if (accept(Tok::Comma)) {
      // A name after a qualifier without time is the indicator; anything else is a duration
      // (checked against the qualifier later, with a clearer message than a syntax error).
      if (sfc::qualifierNeedsTime(a.qualifier) || !atName()) {
        a.duration = parseExpr();
        if (accept(Tok::Comma)) a.indicator.name = expectName("an indicator variable", &a.indicator.loc);
      } else {
        a.indicator.name = expectName("an indicator variable", &a.indicator.loc);
      }
    }
    if (!expect(Tok::RParen, "after the action qualifier")) return false;
  }
  if (!accept(Tok::Semicolon)) errorExpected("';'", "after the action association");
  step.actions.push_back(std::move(a));
  return true;
}

sfc::Transition Parser::parseTransition() {
  sfc::Transition t;
  t.loc = cur().loc;
  SourceLocation keywordLoc = cur().loc;
  advance();
  if (atName() && !isWord(cur(), "FROM")) t.name = expectName("a transition name", &t.loc);
  if (accept(Tok::LParen)) {
    if (isWord(cur(), "PRIORITY")) advance();
    else errorExpected("PRIORITY", "in '(PRIORITY := n)'");
    expect(Tok::Assign, "after PRIORITY");
    if (at(Tok::IntLiteral)) {
      t.priority = static_cast<int64_t>(cur().intValue);
      advance();
    } else {
      errorExpected("an integer priority", "");
    }
    expect(Tok::RParen, "after the priority");
  }
  if (isWord(cur(), "FROM")) advance();
  else errorExpected("FROM", "in TRANSITION");
  parseStepNames(t.from, "after FROM");
  if (!accept(Tok::KwTo)) errorExpected("TO", "after the source steps");
  parseStepNames(t.to, "after TO");
  if (accept(Tok::Assign)) {
    t.condition = parseExpr();
    if (!accept(Tok::Semicolon)) errorExpected("';'", "after the transition condition");
  } else if (accept(Tok::Colon)) {
    t.body = parseStatementList({});
  } else {
    errorExpected("':= condition;' or ': statements'", "after the target steps");
  }
  if (isWord(cur(), "END_TRANSITION")) {
    advance();
    accept(Tok::Semicolon);
  } else {
    error(diag::E007, "expected 'END_TRANSITION' to close 'TRANSITION' at line " + std::to_string(keywordLoc.line) +
                          ", found " + describe(cur()));
  }
  return t;
}

// name | ( name, name, ... )
void Parser::parseStepNames(std::vector<sfc::NamedRef>& out, std::string_view context) {
  bool list = accept(Tok::LParen);
  do {
    sfc::NamedRef ref;
    ref.name = expectName("a step name " + std::string(context), &ref.loc);
    if (ref.name.empty()) return;
    out.push_back(std::move(ref));
  } while (list && accept(Tok::Comma));
  if (list) expect(Tok::RParen, "after the step list");
}

// Lowers the chart of a POU body into ST once the whole POU (with its ACTIONs) is parsed; a
// chart with syntax errors is not lowered (its errors are reported, and the compile stops).
void Parser::finishChart(sfc::Chart& chart, Pou& pou, size_t errorsBefore) {
  if (chart.empty()) return;
  if (pou.kind != PouKind::Program && pou.kind != PouKind::FunctionBlock) {
    diags_.error(diag::E408, chart.loc, "SFC steps and transitions can only form the body of a PROGRAM or FUNCTION_BLOCK");
    return;
  }
  if (diags_.errorCount() != errorsBefore) return;
  sfc::lowerChart(std::move(chart), pou, diags_, nextNodeId_);
}

}  // namespace virtcom::st::detail
