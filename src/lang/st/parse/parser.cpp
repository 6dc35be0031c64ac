// The parser's token handling, error recovery and top level; see parser_internal.hpp.
#include "lang/st/parse/parser.hpp"

#include <algorithm>

#include "core/ascii.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/lexer.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st {

namespace detail {

namespace {

void trimSpaces(std::string_view& s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r' || s.front() == '\n')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n')) s.remove_suffix(1);
}

bool readQuoted(std::string_view& s, std::string& out) {
  if (s.empty() || (s[0] != '\'' && s[0] != '"')) return false;
  size_t close = s.find(s[0], 1);
  if (close == std::string_view::npos) return false;
  out = std::string(s.substr(1, close - 1));
  s.remove_prefix(close + 1);
  trimSpaces(s);
  return true;
}

// `{attribute 'name'}` or `{attribute 'name' := 'value'}`; false for any other pragma.
bool decodeAttribute(std::string_view text, Attribute& out) {
  if (text.size() < 2) return false;
  text = text.substr(1, text.size() - 2);
  trimSpaces(text);
  if (!istartsWithAscii(text, "attribute")) return false;
  text.remove_prefix(9);
  trimSpaces(text);
  if (!readQuoted(text, out.name)) return false;
  if (text.substr(0, 2) == ":=") {
    text.remove_prefix(2);
    trimSpaces(text);
    readQuoted(text, out.value);
  }
  return true;
}

}  // namespace

Parser::Parser(uint32_t fileId, std::vector<Token> tokens, Diagnostics& diags, NodeId& nextNodeId)
    : fileId_(fileId), diags_(diags), nextNodeId_(nextNodeId) {
  // Pragmas are taken out of the token stream; attribute pragmas are remembered by the index of
  // the token they precede, and the declaration starting there claims them. In place, so that
  // the tokens' memory is not touched twice (docs/performance.md, "Start-up").
  size_t kept = 0;
  for (Token& tok : tokens) {
    if (tok.kind != Tok::Pragma) {
      if (&tok != &tokens[kept]) tokens[kept] = std::move(tok);
      ++kept;
      continue;
    }
    Attribute attr;
    if (decodeAttribute(tok.text, attr)) attributes_.emplace_back(kept, std::move(attr));
  }
  tokens.resize(kept);
  toks_ = std::move(tokens);
  if (toks_.empty() || toks_.back().kind != Tok::Eof) toks_.push_back(Token{});
}

const Token& Parser::peekTok(size_t ahead) const { return toks_[std::min(pos_ + ahead, toks_.size() - 1)]; }

bool Parser::accept(Tok kind) {
  if (!at(kind)) return false;
  advance();
  return true;
}

void Parser::advance() {
  if (pos_ + 1 < toks_.size()) ++pos_;
}

bool Parser::isNameToken(Tok kind) {
  switch (kind) {
    case Tok::Identifier:
    // Context keywords: reserved only where the grammar needs them, names elsewhere.
    case Tok::KwGet: case Tok::KwSet: case Tok::KwOn: case Tok::KwWith: case Tok::KwTask: case Tok::KwResource:
    case Tok::KwAbstract: case Tok::KwFinal: case Tok::KwPublic: case Tok::KwPrivate: case Tok::KwProtected:
    case Tok::KwInternal:
      return true;
    default:
      return false;
  }
}

bool Parser::expect(Tok kind, std::string_view context) {
  if (accept(kind)) return true;
  errorExpected("'" + std::string(tokSpelling(kind)) + "'", context);
  return false;
}

std::string Parser::expectName(std::string_view what, SourceLocation* loc) {
  if (!atName()) {
    errorExpected(what, "");
    if (loc != nullptr) *loc = cur().loc;
    return {};
  }
  if (loc != nullptr) *loc = cur().loc;
  std::string name(cur().text);
  advance();
  return name;
}

// END_xxx closing `opener`; also swallows an optional ';' after it. A wrong end keyword is not
// consumed: it most likely closes an enclosing construct.
bool Parser::expectEnd(Tok endKind, std::string_view opener, SourceLocation openLoc, SourceLocation* endLoc) {
  if (at(endKind)) {
    if (endLoc != nullptr) *endLoc = cur().loc;
    advance();
    accept(Tok::Semicolon);
    return true;
  }
  error(diag::E007, "expected '" + std::string(tokSpelling(endKind)) + "' to close '" + std::string(opener) +
                        "' at line " + std::to_string(openLoc.line) + ", found " + describe(cur()));
  return false;
}

void Parser::error(std::string_view code, std::string message) {
  // One diagnostic per token: a cascade of complaints about the same spot helps nobody.
  if (stopped_ || pos_ == lastErrorPos_) return;
  lastErrorPos_ = pos_;
  diags_.error(code, cur().loc, std::move(message));
}

void Parser::errorExpected(std::string_view expected, std::string_view context) {
  std::string message = "expected " + std::string(expected);
  if (!context.empty()) message += " " + std::string(context);
  error(diag::E006, message + ", found " + describe(cur()));
}

std::string Parser::describe(const Token& tok) {
  if (tok.kind == Tok::Eof) return "end of file";
  constexpr size_t kMaxShown = 24;
  std::string_view text = tok.text;
  if (text.size() > kMaxShown) return "'" + std::string(text.substr(0, kMaxShown)) + "...'";
  return "'" + std::string(text) + "'";
}

bool Parser::isTopLevelStart(Tok kind) {
  switch (kind) {
    case Tok::KwProgram: case Tok::KwFunction: case Tok::KwFunctionBlock: case Tok::KwInterface: case Tok::KwType:
    case Tok::KwVarGlobal: case Tok::KwConfiguration:
      return true;
    default:
      return false;
  }
}

bool Parser::isPouEnd(Tok kind) {
  switch (kind) {
    case Tok::KwEndProgram: case Tok::KwEndFunction: case Tok::KwEndFunctionBlock: case Tok::KwEndMethod:
    case Tok::KwEndAction: case Tok::KwEndGet: case Tok::KwEndSet: case Tok::KwEndProperty: case Tok::KwEndInterface:
      return true;
    default:
      return false;
  }
}

// Statement-level end keywords: they close an open construct or are strays.
bool Parser::isSoftEnd(Tok kind) {
  switch (kind) {
    case Tok::KwEndIf: case Tok::KwElsif: case Tok::KwElse: case Tok::KwEndCase: case Tok::KwEndFor:
    case Tok::KwEndWhile: case Tok::KwEndRepeat: case Tok::KwUntil:
      return true;
    default:
      return false;
  }
}

bool Parser::isVarBlockStart(Tok kind) {
  switch (kind) {
    case Tok::KwVar: case Tok::KwVarInput: case Tok::KwVarOutput: case Tok::KwVarInOut: case Tok::KwVarTemp:
    case Tok::KwVarGlobal: case Tok::KwVarExternal: case Tok::KwVarInst: case Tok::KwVarStat: case Tok::KwVarConfig:
      return true;
    default:
      return false;
  }
}

// Tokens at which no statement or declaration list goes on: they belong to an enclosing
// declaration, whose parser decides what to do with them.
bool Parser::isHardStop(Tok kind) const {
  if (isTopLevelStart(kind) || isPouEnd(kind) || isVarBlockStart(kind)) return true;
  switch (kind) {
    case Tok::Eof: case Tok::KwMethod: case Tok::KwProperty: case Tok::KwAction: case Tok::KwEndVar:
    case Tok::KwEndType: case Tok::KwEndStruct: case Tok::KwEndUnion: case Tok::KwEndConfiguration: case Tok::KwEndResource:
      return true;
    default:
      return false;
  }
}

void Parser::skipToTopLevel() {
  while (!at(Tok::Eof) && !isTopLevelStart(cur().kind)) advance();
}

void Parser::skipPastSemicolon(bool stopAtStatementStart) {
  while (!at(Tok::Eof)) {
    if (accept(Tok::Semicolon)) return;
    Tok kind = cur().kind;
    if (isHardStop(kind) || isSoftEnd(kind)) return;
    if (stopAtStatementStart && isStatementStart(kind) && !isNameToken(kind)) return;
    advance();
  }
}

void Parser::skipStray(size_t& lastStray, std::string_view expected) {
  if (pos_ != lastStray + 1) errorExpected(expected, "");
  lastStray = pos_;
  advance();
}

void Parser::stopParsing(std::string message) {
  error(diag::E010, std::move(message));
  stopped_ = true;
  pos_ = toks_.size() - 1;
}

// Attributes written directly before the current token. The parser never moves backwards, so
// attributes before earlier tokens that nobody claimed (e.g. before a statement) are dropped.
std::vector<Attribute> Parser::takeAttributes() {
  std::vector<Attribute> taken;
  while (nextAttribute_ < attributes_.size() && attributes_[nextAttribute_].first < pos_) ++nextAttribute_;
  while (nextAttribute_ < attributes_.size() && attributes_[nextAttribute_].first == pos_)
    taken.push_back(std::move(attributes_[nextAttribute_++].second));
  return taken;
}

Parser::NestingGuard::NestingGuard(Parser& parser, int c) : p(parser), cost(c) {
  p.depth_ += cost;
  ok = p.depth_ <= kMaxNesting && !p.stopped_;
  if (p.depth_ > kMaxNesting)
    p.stopParsing("nesting too deep: more than " + std::to_string(kMaxNesting / kRecursionCost) +
                  " levels of parentheses, statements or types; the rest of the file is not parsed");
}

Parser::OpenConstruct::OpenConstruct(Parser& parser, std::initializer_list<Tok> kinds) : p(parser), ends(kinds) {
  for (Tok k : ends) ++p.openEnds_[static_cast<size_t>(k)];
}

Parser::OpenConstruct::~OpenConstruct() {
  for (Tok k : ends) --p.openEnds_[static_cast<size_t>(k)];
}

ExprPtr Parser::makeExpr(ExprKind kind, SourceLocation loc) {
  auto e = std::make_unique<Expr>();
  e->kind = kind;
  e->loc = loc;
  e->id = ++nextNodeId_;
  return e;
}

StmtPtr Parser::makeStmt(StmtKind kind, SourceLocation loc) {
  auto s = std::make_unique<Stmt>();
  s->kind = kind;
  s->loc = loc;
  s->id = ++nextNodeId_;
  return s;
}

CompilationUnit Parser::parseUnit() {
  CompilationUnit unit;
  unit.fileId = fileId_;
  // Actions written outside their POU (RuSTy, IronPLC): `ACTIONS prg ACTION a ... END_ACTION
  // END_ACTIONS` and `ACTION prg.a ... END_ACTION`; attached to the POU of this file at the end.
  std::vector<std::pair<std::string, std::unique_ptr<Pou>>> outsideActions;
  while (!at(Tok::Eof)) {
    size_t before = pos_;
    std::vector<Attribute> attributes = takeAttributes();
    if (at(Tok::KwAction) && isNameToken(peekTok(1).kind) && peekTok(2).kind == Tok::Dot) {
      SourceLocation loc = cur().loc;
      advance();
      std::string owner(cur().text);
      advance();  // parseAction skips the '.' as it would skip the ACTION keyword
      auto action = parseAction(std::move(attributes));
      action->loc = loc;
      outsideActions.emplace_back(std::move(owner), std::move(action));
      continue;
    }
    if (atName() && iequalsAscii(cur().text, "ACTIONS")) {
      advance();
      std::string owner = expectName("the name of the PROGRAM or FUNCTION_BLOCK the actions belong to");
      accept(Tok::Semicolon);
      while (at(Tok::KwAction) && !stopped_) outsideActions.emplace_back(owner, parseAction(takeAttributes()));
      if (atName() && iequalsAscii(cur().text, "END_ACTIONS")) {
        advance();
        accept(Tok::Semicolon);
      } else {
        errorExpected("END_ACTIONS", "to close ACTIONS " + owner);
      }
      continue;
    }
    switch (cur().kind) {
      case Tok::KwProgram: case Tok::KwFunction: case Tok::KwFunctionBlock:
        unit.pous.push_back(parsePou(std::move(attributes)));
        break;
      case Tok::KwInterface: unit.interfaces.push_back(parseInterface()); break;
      case Tok::KwType: parseTypeBlock(unit.types, std::move(attributes)); break;
      case Tok::KwVarGlobal: addGlobalBlock(unit, std::move(attributes)); break;
      case Tok::KwConfiguration: unit.configurations.push_back(parseConfiguration()); break;
      case Tok::Semicolon: advance(); break;
      case Tok::KwMethod: case Tok::KwProperty: case Tok::KwAction:
        error(diag::E006, "'" + std::string(tokSpelling(cur().kind)) +
                              "' is only allowed inside a FUNCTION_BLOCK, PROGRAM or INTERFACE");
        advance();
        skipToTopLevel();
        break;
      default:
        errorExpected("PROGRAM, FUNCTION, FUNCTION_BLOCK, INTERFACE, TYPE, VAR_GLOBAL or CONFIGURATION", "");
        advance();
        skipToTopLevel();
        break;
    }
    if (pos_ == before) advance();  // every branch consumes its keyword; this is a safety net
  }
  for (auto& outside : outsideActions) {
    const std::string& owner = outside.first;  // the name the lambda below compares against
    auto& action = outside.second;
    auto pou = std::find_if(unit.pous.begin(), unit.pous.end(), [&](const std::unique_ptr<Pou>& p) {
      return iequalsAscii(p->name, owner) && (p->kind == PouKind::Program || p->kind == PouKind::FunctionBlock);
    });
    if (pou == unit.pous.end())
      diags_.error(diag::E006, action->loc, "ACTION '" + action->name + "' belongs to '" + owner +
                                                "', which is no PROGRAM or FUNCTION_BLOCK of this file");
    else
      (*pou)->actions.push_back(std::move(action));
  }
  return unit;
}

StmtList Parser::parseStatementFragment() {
  StmtList all;
  while (!at(Tok::Eof) && !stopped_) {
    for (StmtPtr& stmt : parseStatementList({})) all.push_back(std::move(stmt));
    if (at(Tok::Eof) || stopped_) break;
    errorExpected("a statement", "");  // a declaration keyword or END_xxx has no place here
    advance();
  }
  return all;
}

ExprPtr Parser::parseExpressionFragment() {
  ExprPtr expr = parseExpr();
  if (!expr) expr = errorExpr(cur().loc);
  if (!at(Tok::Eof) && !stopped_) errorExpected("the end of the expression", "");
  return expr;
}

}  // namespace detail

CompilationUnit parseFile(uint32_t fileId, std::string_view text, Diagnostics& diags, NodeId& nextNodeId) {
  detail::Parser parser(fileId, lex(fileId, text, diags), diags, nextNodeId);
  return parser.parseUnit();
}

StmtList parseStatements(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags,
                         NodeId& nextNodeId) {
  detail::Parser parser(fileId, lexFragment(fileId, origin, text, diags), diags, nextNodeId);
  return parser.parseStatementFragment();
}

ExprPtr parseExpression(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags,
                        NodeId& nextNodeId) {
  detail::Parser parser(fileId, lexFragment(fileId, origin, text, diags), diags, nextNodeId);
  return parser.parseExpressionFragment();
}

}  // namespace virtcom::st
