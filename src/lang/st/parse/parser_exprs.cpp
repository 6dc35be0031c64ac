// Expressions: precedence climbing over the IEC operator table, then unary, postfix, primaries.
#include "core/iec_value.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st::detail {

namespace {

// IEC 61131-3 precedence, lowest first: OR; XOR; AND; = <>; < > <= >=; + -; * / MOD; **.
bool binaryOperator(Tok kind, BinaryOp& op, int& precedence) {
  switch (kind) {
    case Tok::KwOr: op = BinaryOp::Or; precedence = 1; return true;
    case Tok::KwOrElse: op = BinaryOp::OrElse; precedence = 1; return true;
    case Tok::KwXor: op = BinaryOp::Xor; precedence = 2; return true;
    case Tok::KwAnd: case Tok::Amp: op = BinaryOp::And; precedence = 3; return true;
    case Tok::KwAndThen: op = BinaryOp::AndThen; precedence = 3; return true;
    case Tok::Eq: op = BinaryOp::Eq; precedence = 4; return true;
    case Tok::Ne: op = BinaryOp::Ne; precedence = 4; return true;
    case Tok::Lt: op = BinaryOp::Lt; precedence = 5; return true;
    case Tok::Le: op = BinaryOp::Le; precedence = 5; return true;
    case Tok::Gt: op = BinaryOp::Gt; precedence = 5; return true;
    case Tok::Ge: op = BinaryOp::Ge; precedence = 5; return true;
    case Tok::Plus: op = BinaryOp::Add; precedence = 6; return true;
    case Tok::Minus: op = BinaryOp::Sub; precedence = 6; return true;
    case Tok::Star: op = BinaryOp::Mul; precedence = 7; return true;
    case Tok::Slash: op = BinaryOp::Div; precedence = 7; return true;
    case Tok::KwMod: op = BinaryOp::Mod; precedence = 7; return true;
    case Tok::Power: op = BinaryOp::Power; precedence = 8; return true;
    default: return false;
  }
}

// `%X3` (bit 3), `%B1`, `%W0`, `%D1`, `%L0` (byte 1, word 0, ...): partial access after a dot.
bool isPartialAccess(std::string_view text) {
  if (text.size() < 3 || std::string_view("XBWDLxbwdl").find(text[1]) == std::string_view::npos) return false;
  for (char c : text.substr(2))
    if (c < '0' || c > '9') return false;
  return true;
}

bool isBitAddress(std::string_view text) { return isPartialAccess(text) && (text[1] == 'X' || text[1] == 'x'); }

}  // namespace

ExprPtr Parser::parseExpr() { return parseBinary(1); }

// Left-associative precedence climbing. Every operator of a chain adds one to depth_ for as long
// as the chain is being built, so a flat `a + a + ... + a` is bounded like nested parentheses.
ExprPtr Parser::parseBinary(int minPrecedence) {
  ExprPtr lhs = parseUnary();
  int chainCost = 0;
  BinaryOp op{};
  int precedence = 0;
  while (!stopped_ && binaryOperator(cur().kind, op, precedence) && precedence >= minPrecedence) {
    ++depth_;
    ++chainCost;
    if (depth_ > kMaxNesting) {
      stopParsing("expression too deeply nested or too long; the rest of the file is not parsed");
      break;
    }
    auto e = makeExpr(ExprKind::Binary, cur().loc);
    e->binaryOp = op;
    advance();
    e->lhs = std::move(lhs);
    e->rhs = parseBinary(precedence + 1);
    lhs = std::move(e);
  }
  depth_ -= chainCost;
  return lhs;
}

ExprPtr Parser::parseUnary() {
  NestingGuard guard(*this, kRecursionCost);
  if (!guard.ok) return errorExpr(cur().loc);
  UnaryOp op{};
  switch (cur().kind) {
    case Tok::Minus: op = UnaryOp::Neg; break;
    case Tok::Plus: op = UnaryOp::Plus; break;
    case Tok::KwNot:
      if (peekTok(1).kind == Tok::LParen) return parseNotParen();
      op = UnaryOp::Not;
      break;
    default: return parsePostfix();
  }
  auto e = makeExpr(ExprKind::Unary, cur().loc);
  e->unaryOp = op;
  advance();
  e->lhs = parseUnary();
  return e;
}

// `NOT (...)`: the unary NOT of a parenthesised expression, or the standard function NOT called
// with named or several arguments (`NOT(IN := x)`, `NOT(a, b)`, which the checker rejects for its
// argument count). With one positional argument the two readings are the same, and it stays a
// Unary Not.
ExprPtr Parser::parseNotParen() {
  SourceLocation loc = cur().loc;
  auto e = makeExpr(ExprKind::Unary, loc);
  e->unaryOp = UnaryOp::Not;
  advance();  // NOT
  bool named = isNameToken(peekTok(1).kind) && (peekTok(2).kind == Tok::Assign || peekTok(2).kind == Tok::OutAssign);
  if (!named) {
    NestingGuard guard(*this, kRecursionCost);
    if (!guard.ok) return errorExpr(loc);
    advance();  // '('
    ExprPtr first = parseExpr();
    if (!at(Tok::Comma)) {
      expect(Tok::RParen, "to close '('");
      e->lhs = parsePostfixOps(std::move(first));
      return e;
    }
    CallArg arg;
    arg.loc = first->loc;
    arg.value = std::move(first);
    e->args.push_back(std::move(arg));
    while (!stopped_ && accept(Tok::Comma)) e->args.push_back(parseCallArg());
    expect(Tok::RParen, "to close the argument list");
  } else {
    advance();  // '('
    parseCallArgs(e->args);
  }
  e->kind = ExprKind::Call;
  e->unaryOp = UnaryOp{};
  e->lhs = makeExpr(ExprKind::Name, loc);
  e->lhs->text = "NOT";
  return parsePostfixOps(std::move(e));
}

ExprPtr Parser::parsePostfix() { return parsePostfixOps(parsePrimary()); }

ExprPtr Parser::parsePostfixOps(ExprPtr base) {
  int chainCost = 0;
  while (!stopped_) {
    Tok kind = cur().kind;
    if (kind != Tok::LParen && kind != Tok::LBracket && kind != Tok::Dot && kind != Tok::Caret) break;
    ++depth_;
    ++chainCost;
    if (depth_ > kMaxNesting) {
      stopParsing("expression too deeply nested or too long; the rest of the file is not parsed");
      break;
    }
    if (kind == Tok::LParen) {
      auto call = makeExpr(ExprKind::Call, base->loc);
      advance();
      call->lhs = std::move(base);
      parseCallArgs(call->args);
      base = std::move(call);
    } else if (kind == Tok::LBracket) {
      auto index = makeExpr(ExprKind::Index, cur().loc);
      advance();
      index->lhs = std::move(base);
      do index->items.push_back(parseExpr());
      while (accept(Tok::Comma));
      expect(Tok::RBracket, "to close the index");
      base = std::move(index);
    } else if (kind == Tok::Dot) {
      base = parseMemberOrBit(std::move(base));
    } else {
      auto deref = makeExpr(ExprKind::Deref, cur().loc);
      advance();
      deref->lhs = std::move(base);
      base = std::move(deref);
    }
  }
  depth_ -= chainCost;
  return base;
}

ExprPtr Parser::parseMemberOrBit(ExprPtr base) {
  advance();  // '.'
  const Token& tok = cur();
  ExprPtr e;
  if (tok.kind == Tok::IntLiteral) {
    e = makeExpr(ExprKind::BitAccess, tok.loc);
    e->intValue = tok.intValue;
  } else if (tok.kind == Tok::DirectAddress && isBitAddress(tok.text)) {
    e = makeExpr(ExprKind::BitAccess, tok.loc);
    for (char c : tok.text.substr(2)) e->intValue = e->intValue * 10 + static_cast<uint64_t>(c - '0');
  } else if (tok.kind == Tok::DirectAddress && isPartialAccess(tok.text)) {
    // `w.%B1`: a partial access, resolved like a member (codegen's partialAccessPlace).
    e = makeExpr(ExprKind::Member, tok.loc);
    e->text = std::string(tok.text);
  } else if (isNameToken(tok.kind) || isKeyword(tok.kind)) {
    // After '.' only a name can follow, so even reserved words are member names here.
    e = makeExpr(ExprKind::Member, tok.loc);
    e->text = std::string(tok.text);
  } else {
    errorExpected("a member name or bit number", "after '.'");
    return base;
  }
  advance();
  e->lhs = std::move(base);
  return e;
}

ExprPtr Parser::parsePrimary() {
  const Token& tok = cur();
  switch (tok.kind) {
    case Tok::IntLiteral: case Tok::RealLiteral: case Tok::StringLiteral: case Tok::WStringLiteral:
    case Tok::KwTrue: case Tok::KwFalse: case Tok::TimeLiteral: case Tok::DateLiteral:
      return parseLiteralToken();
    case Tok::TypedPrefix: return parseTypedLiteral();
    case Tok::DirectAddress: {
      if (isPartialAccess(tok.text))
        error(diag::E012, "'" + std::string(tok.text) + "' is only valid as a partial access after '.', e.g. w.%X3 or dw.%B1");
      auto e = makeExpr(ExprKind::DirectAddr, tok.loc);
      e->text = std::string(tok.text);
      advance();
      return e;
    }
    case Tok::KwThis: case Tok::KwSuper: {
      auto e = makeExpr(tok.kind == Tok::KwThis ? ExprKind::This : ExprKind::Super, tok.loc);
      advance();
      return e;
    }
    case Tok::LParen: {
      if (atStructInit()) return parseStructInit();
      advance();
      ExprPtr inner = parseExpr();
      expect(Tok::RParen, "to close '('");
      return inner;
    }
    case Tok::LBracket: return parseArrayInit();
    case Tok::KwAnd: case Tok::KwOr: case Tok::KwXor: case Tok::KwMod: {
      // The operator in function form, `MOD(a, b)`, `AND(a, b, c)`: a call of the standard
      // function of that name (the '(' is left for parsePostfixOps).
      if (peekTok(1).kind != Tok::LParen) break;
      auto e = makeExpr(ExprKind::Name, tok.loc);
      e->text = std::string(tokSpelling(tok.kind));
      advance();
      return e;
    }
    default: break;
  }
  if (isNameToken(tok.kind)) {
    auto e = makeExpr(ExprKind::Name, tok.loc);
    e->text = std::string(tok.text);
    advance();
    return e;
  }
  errorExpected("an expression", "");
  return errorExpr(tok.loc);
}

// Plain literal tokens. A negative time literal becomes Neg(TimeLit) like every other sign.
ExprPtr Parser::parseLiteralToken() {
  const Token& tok = cur();
  ExprPtr e;
  switch (tok.kind) {
    case Tok::IntLiteral:
      e = makeExpr(ExprKind::IntLit, tok.loc);
      e->intValue = tok.intValue;
      break;
    case Tok::RealLiteral:
      e = makeExpr(ExprKind::RealLit, tok.loc);
      e->realValue = tok.realValue;
      break;
    case Tok::StringLiteral: case Tok::WStringLiteral:
      e = makeExpr(ExprKind::StringLit, tok.loc);
      e->text = tok.str;
      e->wide = tok.kind == Tok::WStringLiteral;
      break;
    case Tok::KwTrue: case Tok::KwFalse:
      e = makeExpr(ExprKind::BoolLit, tok.loc);
      e->intValue = tok.kind == Tok::KwTrue ? 1 : 0;
      break;
    case Tok::TimeLiteral: case Tok::DateLiteral:
      e = makeExpr(tok.kind == Tok::TimeLiteral ? ExprKind::TimeLit : ExprKind::DateLit, tok.loc);
      e->intValue = tok.intValue;
      e->typePrefix = tok.str;
      break;
    default:
      errorExpected("a literal", "");
      return errorExpr(tok.loc);
  }
  bool negative = tok.kind == Tok::TimeLiteral && tok.negative;
  advance();
  if (!negative) return e;
  auto neg = makeExpr(ExprKind::Unary, e->loc);
  neg->unaryOp = UnaryOp::Neg;
  neg->lhs = std::move(e);
  return neg;
}

// `INT#5`, `INT#-5` (Neg around the literal), `DINT#16#FF`, `REAL#1.5`, `BOOL#1`, `STRING#'a'`,
// or, when the prefix is not an elementary type, the enumeration value `Color#Red`.
ExprPtr Parser::parseTypedLiteral() {
  SourceLocation loc = cur().loc;
  std::string prefix(cur().text);
  advance();
  ElemType type{};
  if (!elemTypeByName(prefix, type)) {
    if (!atName() && !isKeyword(cur().kind)) {
      errorExpected("an enumeration value", "after '" + prefix + "#'");
      return errorExpr(loc);
    }
    auto e = makeExpr(ExprKind::EnumLit, loc);
    e->typePrefix = prefix;
    e->text = std::string(cur().text);
    advance();
    return e;
  }
  bool negative = at(Tok::Minus);
  if (negative || at(Tok::Plus)) advance();
  const Token& valueTok = cur();
  ElemKind elemKind = elemTypeInfo(type).kind;
  bool fits = false;
  switch (valueTok.kind) {
    case Tok::IntLiteral:
      fits = isIntegerKind(elemKind) || elemKind == ElemKind::Float || (elemKind == ElemKind::Bool && valueTok.intValue <= 1);
      break;
    case Tok::RealLiteral: fits = elemKind == ElemKind::Float; break;
    case Tok::KwTrue: case Tok::KwFalse: fits = elemKind == ElemKind::Bool; break;
    case Tok::StringLiteral: case Tok::WStringLiteral: fits = elemKind == ElemKind::Text || elemKind == ElemKind::Char; break;
    default:
      errorExpected("a literal", "after '" + prefix + "#'");
      return errorExpr(loc);
  }
  if (!fits || (negative && (elemKind == ElemKind::Bool || elemKind == ElemKind::Text || elemKind == ElemKind::Char))) {
    error(diag::E013, "'" + std::string(valueTok.text) + "' is not a valid " + std::string(elemTypeInfo(type).name) + " literal");
    advance();
    return errorExpr(loc);
  }
  ExprPtr e = parseLiteralToken();
  if (elemKind == ElemKind::Bool) {
    e->kind = ExprKind::BoolLit;
  } else if (elemKind == ElemKind::Float && e->kind == ExprKind::IntLit) {
    e->kind = ExprKind::RealLit;
    e->realValue = static_cast<double>(e->intValue);
    e->intValue = 0;
  }
  e->loc = loc;
  e->typePrefix = std::string(elemTypeInfo(type).name);
  if (type == ElemType::Tod) e->typePrefix = "TOD";
  if (type == ElemType::Dt) e->typePrefix = "DT";
  if (!negative) return e;
  auto neg = makeExpr(ExprKind::Unary, loc);
  neg->unaryOp = UnaryOp::Neg;
  neg->lhs = std::move(e);
  return neg;
}

// `[1, 2, 3(0)]`: `n(x)` repeats x n times (an empty `n()` repeats the default value).
ExprPtr Parser::parseArrayInit() {
  auto e = makeExpr(ExprKind::ArrayInit, cur().loc);
  advance();
  if (accept(Tok::RBracket)) return e;
  do {
    if (at(Tok::IntLiteral) && peekTok(1).kind == Tok::LParen) {
      auto repeat = makeExpr(ExprKind::Repeat, cur().loc);
      repeat->intValue = cur().intValue;
      advance();
      advance();
      if (!at(Tok::RParen)) repeat->lhs = parseExpr();
      expect(Tok::RParen, "to close the repeated value");
      e->items.push_back(std::move(repeat));
    } else {
      e->items.push_back(parseExpr());
    }
  } while (!stopped_ && accept(Tok::Comma));
  expect(Tok::RBracket, "to close the array initialiser");
  return e;
}

bool Parser::atStructInit() const {
  return at(Tok::LParen) && isNameToken(peekTok(1).kind) && peekTok(2).kind == Tok::Assign;
}

// `(x := 1, y := (a := 2))`
ExprPtr Parser::parseStructInit() {
  auto e = makeExpr(ExprKind::StructInit, cur().loc);
  advance();
  do {
    if (!atName()) {
      errorExpected("a member name", "in structure initialiser");
      break;
    }
    CallArg arg;
    arg.loc = cur().loc;
    arg.name = std::string(cur().text);
    advance();
    expect(Tok::Assign, "after member name");
    arg.value = parseExpr();
    e->args.push_back(std::move(arg));
  } while (!stopped_ && accept(Tok::Comma));
  expect(Tok::RParen, "to close the structure initialiser");
  return e;
}

// A trailing comma before ')' is accepted, as CODESYS does (`F(a := 1, b := 2,)`).
void Parser::parseCallArgs(std::vector<CallArg>& args) {
  if (accept(Tok::RParen)) return;
  do {
    if (at(Tok::RParen) && !args.empty()) break;
    args.push_back(parseCallArg());
  } while (!stopped_ && accept(Tok::Comma));
  expect(Tok::RParen, "to close the argument list");
}

// `IN := x` (input), `Q => q` / `Q =>` (output), `NOT Q => nq` (inverted output), or positional.
CallArg Parser::parseCallArg() {
  CallArg arg;
  arg.loc = cur().loc;
  if (at(Tok::KwNot) && isNameToken(peekTok(1).kind) && peekTok(2).kind == Tok::OutAssign) {
    arg.negated = true;
    advance();
  }
  bool named = atName() && (peekTok(1).kind == Tok::Assign || peekTok(1).kind == Tok::OutAssign);
  if (!named) {
    arg.value = parseExpr();
    return arg;
  }
  arg.name = std::string(cur().text);
  arg.output = peekTok(1).kind == Tok::OutAssign;
  advance();
  advance();
  bool emptyOutput = arg.output && (at(Tok::Comma) || at(Tok::RParen));
  if (!emptyOutput) arg.value = parseExpr();
  return arg;
}

}  // namespace virtcom::st::detail
