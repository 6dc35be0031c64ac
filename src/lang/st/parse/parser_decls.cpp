// Declarations: VAR blocks, variable declarations, type specifications and TYPE blocks.
#include "core/ascii.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st::detail {

namespace {

VarSection sectionOf(Tok kind) {
  switch (kind) {
    case Tok::KwVarInput: return VarSection::Input;
    case Tok::KwVarOutput: return VarSection::Output;
    case Tok::KwVarInOut: return VarSection::InOut;
    case Tok::KwVarTemp: return VarSection::Temp;
    case Tok::KwVarGlobal: return VarSection::Global;
    case Tok::KwVarExternal: return VarSection::External;
    case Tok::KwVarInst: return VarSection::Inst;
    case Tok::KwVarStat: return VarSection::Stat;
    default: return VarSection::Var;
  }
}

}  // namespace

VarBlock Parser::parseVarBlock() {
  VarBlock block;
  block.loc = cur().loc;
  block.section = sectionOf(cur().kind);
  std::string opener(tokSpelling(cur().kind));
  if (at(Tok::KwVarConfig))
    error(diag::E011, "VAR_CONFIG belongs in a CONFIGURATION (inst.var AT %IX1.0 : BOOL;); here its declarations are read as VAR");
  advance();
  for (bool more = true; more;) {
    switch (cur().kind) {
      case Tok::KwConstant: block.constant = true; break;
      case Tok::KwRetain: block.retain = true; break;
      case Tok::KwNonRetain: block.retain = false; break;
      case Tok::KwPersistent: block.persistent = true; break;
      default: more = false; continue;
    }
    advance();
  }
  while (!at(Tok::KwEndVar) && !isHardStop(cur().kind) && !stopped_) {
    // Statements where declarations should be: END_VAR was forgotten.
    bool statementAhead = (isStatementStart(cur().kind) && !isNameToken(cur().kind)) ||
                          (atName() && peekTok(1).kind == Tok::Assign);
    if (statementAhead) break;
    size_t before = pos_;
    VarDecl decl;
    if (parseVarDecl(decl, true)) block.vars.push_back(std::move(decl));
    if (pos_ == before) advance();
  }
  expectEnd(Tok::KwEndVar, opener, block.loc);
  return block;
}

// `a, b AT %IX0.0 : T(fbInit) := init;` Returns false (after skipping to the next ';') when no
// usable declaration was found.
bool Parser::parseVarDecl(VarDecl& decl, bool allowLocation) {
  decl.attributes = takeAttributes();
  decl.loc = cur().loc;
  parseDeclNames(decl.names);
  if (decl.names.empty()) {
    errorExpected("a variable name", "");
    skipPastSemicolon(false);
    return false;
  }
  if (allowLocation && accept(Tok::KwAt)) {
    if (at(Tok::DirectAddress)) {
      decl.location = std::string(cur().text);
      advance();
    } else {
      errorExpected("a direct address such as %IX0.0", "after AT");
    }
  }
  if (!expect(Tok::Colon, "after variable name")) {
    skipPastSemicolon(false);
    return true;
  }
  decl.type = parseTypeSpec(false, &decl.fbInitArgs);
  if (atName() && (iequalsAscii(cur().text, "R_EDGE") || iequalsAscii(cur().text, "F_EDGE"))) {
    decl.edge = iequalsAscii(cur().text, "R_EDGE") ? EdgeKind::Rising : EdgeKind::Falling;
    decl.edgeLoc = cur().loc;
    advance();
  }
  if (accept(Tok::Assign)) decl.init = parseExpr();
  if (accept(Tok::Semicolon)) return true;
  errorExpected("';'", "after variable declaration");
  // Keep going if the next declaration (or END_VAR) already starts; otherwise resynchronise.
  bool nextDeclStarts = atName() && (peekTok(1).kind == Tok::Colon || peekTok(1).kind == Tok::Comma ||
                                     peekTok(1).kind == Tok::KwAt);
  if (!nextDeclStarts && !at(Tok::KwEndVar) && !at(Tok::KwEndStruct) && !at(Tok::KwEndUnion)) skipPastSemicolon(false);
  return true;
}

void Parser::parseDeclNames(std::vector<DeclName>& names) {
  if (!atName()) return;
  do {
    DeclName name;
    name.name = expectName("a variable name", &name.loc);
    if (name.name.empty()) break;
    names.push_back(std::move(name));
  } while (accept(Tok::Comma));
}

std::string Parser::parseQualifiedName() {
  std::string name = expectName("a type name");
  while (!name.empty() && at(Tok::Dot) && isNameToken(peekTok(1).kind)) {
    advance();
    name += '.';
    name += cur().text;
    advance();
  }
  return name;
}

// A type as written after ':'. `allowStruct`: inside TYPE ... END_TYPE. `fbInitArgs`: where a
// declaration may pass FB_init arguments (`inst : FB_T(a := 1)`); null elsewhere.
TypeSpec Parser::parseTypeSpec(bool allowStruct, std::vector<CallArg>* fbInitArgs) {
  TypeSpec spec;
  spec.loc = cur().loc;
  NestingGuard guard(*this, kRecursionCost);
  if (!guard.ok) return spec;
  switch (cur().kind) {
    case Tok::KwString: case Tok::KwWstring: parseStringType(spec); return spec;
    case Tok::KwArray: parseArrayType(spec); return spec;
    case Tok::LParen: parseEnumType(spec); return spec;
    case Tok::KwPointer: case Tok::KwReferenceTo: case Tok::KwRefTo: {
      // IEC REF_TO is an explicit reference (dereferenced with ^, NULL-able): a pointer here.
      // CODESYS REFERENCE TO is used like the variable it refers to.
      spec.kind = at(Tok::KwReferenceTo) ? TypeSpecKind::Reference : TypeSpecKind::Pointer;
      bool needsTo = !at(Tok::KwRefTo);
      std::string what = at(Tok::KwPointer) ? "after POINTER" : "after REFERENCE";
      advance();
      if (needsTo) expect(Tok::KwTo, what);
      spec.element = std::make_unique<TypeSpec>(parseTypeSpec(false, nullptr));
      return spec;
    }
    case Tok::KwStruct:
      if (!allowStruct) error(diag::E006, "STRUCT is only allowed in a TYPE declaration; declare a named type");
      parseStructType(spec);
      return spec;
    case Tok::KwUnion:
      if (!allowStruct) error(diag::E006, "UNION is only allowed in a TYPE declaration; declare a named type");
      parseStructType(spec);
      return spec;
    default: break;
  }
  if (!atName()) {
    errorExpected("a type", "");
    return spec;
  }
  spec.name = parseQualifiedName();
  if (at(Tok::LParen)) parseNamedTypeSuffix(spec, fbInitArgs);
  return spec;
}

// `INT (0..100)` (subrange) or `FB_T(a := 1, b := 2)` / `FB_T(1, 2)` (FB_init arguments).
void Parser::parseNamedTypeSuffix(TypeSpec& spec, std::vector<CallArg>* fbInitArgs) {
  bool namedArgs = (isNameToken(peekTok(1).kind) && peekTok(2).kind == Tok::Assign) || peekTok(1).kind == Tok::RParen;
  if (namedArgs && fbInitArgs != nullptr) {
    advance();
    parseCallArgs(*fbInitArgs);
    return;
  }
  advance();  // '('
  ExprPtr lo = parseExpr();
  if (accept(Tok::DotDot)) {
    auto base = std::make_unique<TypeSpec>();
    base->loc = spec.loc;
    base->name = std::move(spec.name);
    spec.name.clear();
    spec.kind = TypeSpecKind::Subrange;
    spec.element = std::move(base);
    spec.lo = std::move(lo);
    spec.hi = parseExpr();
    expect(Tok::RParen, "to close the subrange");
    return;
  }
  if (fbInitArgs == nullptr) {
    errorExpected("'..'", "in subrange");
    skipPastSemicolon(false);
    return;
  }
  CallArg first;
  first.loc = lo->loc;
  first.value = std::move(lo);
  fbInitArgs->push_back(std::move(first));
  while (!stopped_ && accept(Tok::Comma)) fbInitArgs->push_back(parseCallArg());
  expect(Tok::RParen, "to close the argument list");
}

// STRING, STRING(20), STRING[20]; WSTRING likewise.
void Parser::parseStringType(TypeSpec& spec) {
  spec.kind = TypeSpecKind::String;
  spec.wide = at(Tok::KwWstring);
  advance();
  if (at(Tok::LParen) || at(Tok::LBracket)) {
    Tok close = at(Tok::LParen) ? Tok::RParen : Tok::RBracket;
    advance();
    spec.length = parseExpr();
    expect(close, "after string length");
  }
}

// ARRAY [1..3, 0..1] OF T; `[*]` (a variable-length dimension) leaves both bounds null.
void Parser::parseArrayType(TypeSpec& spec) {
  spec.kind = TypeSpecKind::Array;
  advance();
  if (expect(Tok::LBracket, "after ARRAY")) {
    do {
      ArrayRange range;
      if (!accept(Tok::Star)) {
        range.lo = parseExpr();
        expect(Tok::DotDot, "between array bounds");
        range.hi = parseExpr();
      }
      spec.dims.push_back(std::move(range));
    } while (!stopped_ && accept(Tok::Comma));
    expect(Tok::RBracket, "after array bounds");
  }
  expect(Tok::KwOf, "after array bounds");
  spec.element = std::make_unique<TypeSpec>(parseTypeSpec(false, nullptr));
}

// (a, b := 5, c) optionally followed by the base type: (a, b) INT.
void Parser::parseEnumType(TypeSpec& spec) {
  spec.kind = TypeSpecKind::Enum;
  advance();
  do {
    EnumValueDecl value;
    value.name = expectName("an enumeration value", &value.loc);
    if (value.name.empty()) break;
    if (accept(Tok::Assign)) value.value = parseExpr();
    spec.enumValues.push_back(std::move(value));
  } while (!stopped_ && accept(Tok::Comma));
  if (!expect(Tok::RParen, "after enumeration values")) {
    while (!at(Tok::RParen) && !at(Tok::Semicolon) && !isHardStop(cur().kind)) advance();
    accept(Tok::RParen);
  }
  if (atName()) spec.name = parseQualifiedName();
}

// STRUCT [EXTENDS Base] fields END_STRUCT, or UNION fields END_UNION
void Parser::parseStructType(TypeSpec& spec) {
  spec.kind = TypeSpecKind::Struct;
  spec.isUnion = at(Tok::KwUnion);
  Tok end = spec.isUnion ? Tok::KwEndUnion : Tok::KwEndStruct;
  SourceLocation loc = cur().loc;
  advance();
  if (!spec.isUnion && accept(Tok::KwExtends)) spec.name = parseQualifiedName();
  while (!at(end) && !isHardStop(cur().kind) && !stopped_) {
    size_t before = pos_;
    VarDecl field;
    if (parseVarDecl(field, true)) spec.fields.push_back(std::move(field));
    if (pos_ == before) advance();
  }
  expectEnd(end, spec.isUnion ? "UNION" : "STRUCT", loc);
}

// TYPE Name [EXTENDS Base] : spec [:= init]; ... END_TYPE. Attributes written before TYPE go to
// the first declaration.
void Parser::parseTypeBlock(std::vector<TypeDecl>& out, std::vector<Attribute> attributes) {
  SourceLocation loc = cur().loc;
  advance();
  while (!at(Tok::KwEndType) && !isHardStop(cur().kind) && !stopped_) {
    size_t before = pos_;
    TypeDecl decl;
    decl.attributes = std::move(attributes);
    attributes.clear();
    for (Attribute& a : takeAttributes()) decl.attributes.push_back(std::move(a));
    decl.name = expectName("a type name", &decl.loc);
    std::string extends;
    if (!decl.name.empty() && accept(Tok::KwExtends)) extends = parseQualifiedName();
    if (decl.name.empty() || !expect(Tok::Colon, "after type name")) {
      skipPastSemicolon(false);
      if (pos_ == before) advance();
      continue;
    }
    decl.spec = parseTypeSpec(true, nullptr);
    if (!extends.empty()) {
      if (decl.spec.kind == TypeSpecKind::Struct && !decl.spec.isUnion)
        decl.spec.name = extends;
      else
        diags_.error(diag::E006, decl.loc, "only a STRUCT type can EXTENDS another type");
    }
    if (accept(Tok::Assign)) decl.init = parseExpr();
    // Like CODESYS, no ';' is needed after END_STRUCT / END_UNION.
    Tok previous = toks_[pos_ - 1].kind;
    bool endedByKeyword = previous == Tok::KwEndStruct || previous == Tok::KwEndUnion || previous == Tok::Semicolon;
    if (!accept(Tok::Semicolon) && !endedByKeyword) {
      errorExpected("';'", "after type declaration");
      if (!(atName() && peekTok(1).kind == Tok::Colon) && !at(Tok::KwEndType)) skipPastSemicolon(false);
    }
    out.push_back(std::move(decl));
  }
  expectEnd(Tok::KwEndType, "TYPE", loc);
}

// All top-level VAR_GLOBAL blocks of a file form its one global variable list.
void Parser::addGlobalBlock(CompilationUnit& unit, std::vector<Attribute> attributes) {
  if (unit.globals.empty()) {
    unit.globals.emplace_back();
    unit.globals.back().loc = cur().loc;
  }
  GlobalVarList& list = unit.globals.back();
  for (Attribute& a : attributes) list.attributes.push_back(std::move(a));
  list.blocks.push_back(parseVarBlock());
}

}  // namespace virtcom::st::detail
