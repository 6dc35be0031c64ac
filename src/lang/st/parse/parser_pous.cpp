// POUs (PROGRAM, FUNCTION, FUNCTION_BLOCK and their METHODs, PROPERTYs, ACTIONs), INTERFACEs
// and CONFIGURATIONs.
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/parser_internal.hpp"

namespace virtcom::st::detail {

namespace {

bool accessOf(Tok kind, Access& access) {
  switch (kind) {
    case Tok::KwPublic: access = Access::Public; return true;
    case Tok::KwPrivate: access = Access::Private; return true;
    case Tok::KwProtected: access = Access::Protected; return true;
    case Tok::KwInternal: access = Access::Internal; return true;
    default: return false;
  }
}

}  // namespace

std::unique_ptr<Pou> Parser::parsePou(std::vector<Attribute> attributes) {
  auto pou = std::make_unique<Pou>();
  pou->attributes = std::move(attributes);
  Tok keyword = cur().kind;
  SourceLocation keywordLoc = cur().loc;
  Tok endKind = Tok::KwEndProgram;
  if (keyword == Tok::KwFunction) {
    pou->kind = PouKind::Function;
    endKind = Tok::KwEndFunction;
  } else if (keyword == Tok::KwFunctionBlock) {
    pou->kind = PouKind::FunctionBlock;
    endKind = Tok::KwEndFunctionBlock;
  }
  advance();
  if (keyword == Tok::KwFunctionBlock) parseModifiers(pou->access, pou->isAbstract, pou->isFinal);
  pou->loc = keywordLoc;
  pou->name = expectName("a name after '" + std::string(tokSpelling(keyword)) + "'", &pou->loc);
  if (keyword == Tok::KwFunction && accept(Tok::Colon)) {
    pou->hasReturnType = true;
    pou->returnType = parseTypeSpec(false, nullptr);
  } else if (keyword != Tok::KwFunction && at(Tok::Colon)) {
    // `PROGRAM P : BOOL`: one error at the ':', then the type is skipped and parsing goes on.
    error(diag::E006, "a " + std::string(tokSpelling(keyword)) + " has no return type; only a FUNCTION or METHOD has one");
    advance();
    parseTypeSpec(false, nullptr);
  }
  if (keyword == Tok::KwFunctionBlock) parseInheritance(*pou);
  accept(Tok::Semicolon);
  pou->hasBody = true;
  parsePouBody(*pou, endKind, keyword != Tok::KwFunction);
  return pou;
}

// Access specifiers, ABSTRACT and FINAL in any order. They are context keywords, so one is a
// modifier only if a name still follows (`METHOD Internal : BOOL` is a method named Internal).
void Parser::parseModifiers(Access& access, bool& isAbstract, bool& isFinal) {
  while (isNameToken(peekTok(1).kind)) {
    if (accessOf(cur().kind, access)) {
    } else if (at(Tok::KwAbstract)) {
      isAbstract = true;
    } else if (at(Tok::KwFinal)) {
      isFinal = true;
    } else {
      return;
    }
    advance();
  }
}

void Parser::parseInheritance(Pou& pou) {
  if (accept(Tok::KwExtends)) pou.extends = parseQualifiedName();
  if (accept(Tok::KwImplements)) {
    do pou.implements.push_back(parseQualifiedName());
    while (accept(Tok::Comma));
  }
}

void Parser::parseVarBlocks(std::vector<VarBlock>& blocks) {
  while (isVarBlockStart(cur().kind) && !stopped_) blocks.push_back(parseVarBlock());
}

// Var blocks, then statements, SFC elements and (if `allowMembers`) METHODs, PROPERTYs and
// ACTIONs in any order, then endKind. TwinCAT/CODESYS text exports put the members before the
// body, others after it: the statements before, between and after the members all go, in order,
// to the body; the SFC elements form one chart, lowered after the body (finishChart).
void Parser::parsePouBody(Pou& pou, Tok endKind, bool allowMembers) {
  std::string_view opener = tokSpelling(endKind).substr(4);  // END_PROGRAM -> PROGRAM
  size_t errorsBefore = diags_.errorCount();
  parseVarBlocks(pou.varBlocks);
  size_t lastStray = kNoStray;
  sfc::Chart chart;
  while (!stopped_) {
    for (StmtPtr& stmt : parseStatementList({endKind})) pou.body.push_back(std::move(stmt));
    if (stopped_ || at(endKind) || at(Tok::Eof) || isPouEnd(cur().kind) || isTopLevelStart(cur().kind)) break;
    if (atSfcElement()) {
      parseSfcElement(chart);
      continue;
    }
    bool atMember = at(Tok::KwMethod) || at(Tok::KwProperty) || at(Tok::KwAction);
    if (atMember && !allowMembers && endKind != Tok::KwEndFunction) break;  // a member's END_xxx is missing
    if (atMember) {
      // In a FUNCTION the member is reported, parsed and dropped, so END_FUNCTION is still found.
      if (!allowMembers) error(diag::E006, "a FUNCTION cannot have METHODs, PROPERTYs or ACTIONs");
      std::vector<Attribute> attributes = takeAttributes();
      if (at(Tok::KwMethod)) {
        auto method = parseMethod(false, std::move(attributes));
        if (allowMembers) pou.methods.push_back(std::move(method));
      } else if (at(Tok::KwProperty)) {
        Property prop = parseProperty(false);
        if (allowMembers) pou.properties.push_back(std::move(prop));
      } else {
        auto action = parseAction(std::move(attributes));
        if (allowMembers) pou.actions.push_back(std::move(action));
      }
      continue;
    }
    if (isVarBlockStart(cur().kind)) {
      bool afterMembers = pou.body.empty() && (!pou.methods.empty() || !pou.properties.empty() || !pou.actions.empty());
      error(diag::E006, afterMembers ? "variable declarations must come before the first METHOD, PROPERTY or ACTION"
                                     : "variable declarations must come before the first statement");
      pou.varBlocks.push_back(parseVarBlock());
      continue;
    }
    // A declaration-level token that belongs to nothing here (END_VAR, END_TYPE, ...).
    skipStray(lastStray, "a statement" + std::string(allowMembers ? ", METHOD, PROPERTY, ACTION" : "") + " or '" +
                             std::string(tokSpelling(endKind)) + "'");
  }
  expectEnd(endKind, opener, pou.loc, &pou.endLoc);
  finishChart(chart, pou, errorsBefore);
}

// METHOD [access] [ABSTRACT|FINAL] name [: T] vars body END_METHOD. Methods of interfaces and
// abstract methods have no body (hasBody = false).
std::unique_ptr<Pou> Parser::parseMethod(bool inInterface, std::vector<Attribute> attributes) {
  auto method = std::make_unique<Pou>();
  method->kind = PouKind::Method;
  method->attributes = std::move(attributes);
  method->loc = cur().loc;
  advance();
  parseModifiers(method->access, method->isAbstract, method->isFinal);
  method->name = expectName("a method name", &method->loc);
  if (accept(Tok::Colon)) {
    method->hasReturnType = true;
    method->returnType = parseTypeSpec(false, nullptr);
  }
  accept(Tok::Semicolon);
  parsePouBody(*method, Tok::KwEndMethod, false);
  method->hasBody = !inInterface && !method->isAbstract;
  if (!method->hasBody && !method->body.empty())
    diags_.error(diag::E006, method->body.front()->loc,
                 inInterface ? "a method of an INTERFACE cannot have statements"
                             : "an ABSTRACT method cannot have statements");
  return method;
}

// PROPERTY [access] [ABSTRACT|FINAL] name : T (GET ... END_GET)? (SET ... END_SET)? END_PROPERTY
Property Parser::parseProperty(bool inInterface) {
  Property prop;
  prop.loc = cur().loc;
  SourceLocation keywordLoc = cur().loc;
  advance();
  parseModifiers(prop.access, prop.isAbstract, prop.isFinal);
  prop.name = expectName("a property name", &prop.loc);
  if (expect(Tok::Colon, "after property name")) prop.type = parseTypeSpec(false, nullptr);
  bool noBody = inInterface || prop.isAbstract;
  size_t lastStray = kNoStray;
  while (!at(Tok::KwEndProperty) && !stopped_) {
    if (at(Tok::KwGet)) {
      prop.getter = parseAccessor(prop, true, noBody);
    } else if (at(Tok::KwSet)) {
      prop.setter = parseAccessor(prop, false, noBody);
    } else if (isHardStop(cur().kind)) {
      break;
    } else {
      skipStray(lastStray, "GET, SET or END_PROPERTY");
    }
  }
  expectEnd(Tok::KwEndProperty, "PROPERTY", keywordLoc);
  return prop;
}

std::unique_ptr<Pou> Parser::parseAccessor(const Property& prop, bool getter, bool noBody) {
  auto accessor = std::make_unique<Pou>();
  accessor->kind = getter ? PouKind::PropertyGet : PouKind::PropertySet;
  accessor->name = prop.name;
  accessor->loc = cur().loc;
  accessor->access = prop.access;
  accessor->isAbstract = prop.isAbstract;
  accessor->isFinal = prop.isFinal;
  advance();
  parsePouBody(*accessor, getter ? Tok::KwEndGet : Tok::KwEndSet, false);
  accessor->hasBody = !noBody;
  if (noBody && !accessor->body.empty())
    diags_.error(diag::E006, accessor->body.front()->loc, "an abstract or interface property cannot have statements");
  return accessor;
}

// ACTION name[:] body END_ACTION
std::unique_ptr<Pou> Parser::parseAction(std::vector<Attribute> attributes) {
  auto action = std::make_unique<Pou>();
  action->kind = PouKind::Action;
  action->attributes = std::move(attributes);
  action->loc = cur().loc;
  advance();
  action->name = expectName("an action name", &action->loc);
  accept(Tok::Colon);
  accept(Tok::Semicolon);
  action->hasBody = true;
  parsePouBody(*action, Tok::KwEndAction, false);
  if (!action->varBlocks.empty())
    diags_.error(diag::E006, action->varBlocks.front().loc, "an ACTION cannot declare variables; it uses those of its POU");
  return action;
}

Interface Parser::parseInterface() {
  Interface itf;
  itf.loc = cur().loc;
  SourceLocation keywordLoc = cur().loc;
  advance();
  itf.name = expectName("an interface name", &itf.loc);
  if (accept(Tok::KwExtends)) {
    do itf.extends.push_back(parseQualifiedName());
    while (accept(Tok::Comma));
  }
  size_t lastStray = kNoStray;
  while (!at(Tok::KwEndInterface) && !stopped_) {
    std::vector<Attribute> attributes = takeAttributes();
    if (at(Tok::KwMethod)) {
      itf.methods.push_back(parseMethod(true, std::move(attributes)));
    } else if (at(Tok::KwProperty)) {
      itf.properties.push_back(parseProperty(true));
    } else if (at(Tok::Eof) || isTopLevelStart(cur().kind) || isPouEnd(cur().kind)) {
      break;
    } else {
      skipStray(lastStray, "METHOD, PROPERTY or END_INTERFACE");
    }
  }
  expectEnd(Tok::KwEndInterface, "INTERFACE", keywordLoc);
  return itf;
}

// CONFIGURATION name globals (RESOURCE ... END_RESOURCE)* END_CONFIGURATION. TASK and PROGRAM
// written directly in the configuration go to an implicit resource with an empty name.
Configuration Parser::parseConfiguration() {
  Configuration config;
  config.loc = cur().loc;
  SourceLocation keywordLoc = cur().loc;
  advance();
  config.name = expectName("a configuration name", &config.loc);
  size_t lastStray = kNoStray;
  while (!at(Tok::KwEndConfiguration) && !at(Tok::Eof) && !stopped_) {
    if (at(Tok::KwVarGlobal)) {
      config.globals.push_back(parseVarBlock());
    } else if (at(Tok::KwVarConfig)) {
      parseVarConfig(config.configVars);
    } else if (at(Tok::KwResource)) {
      config.resources.push_back(parseResource());
    } else if (at(Tok::KwTask) || at(Tok::KwProgram)) {
      if (config.resources.empty() || !config.resources.back().name.empty()) {
        config.resources.emplace_back();
        config.resources.back().loc = cur().loc;
      }
      parseResourceItem(config.resources.back());
    } else if (isTopLevelStart(cur().kind)) {
      break;
    } else {
      skipStray(lastStray, "VAR_GLOBAL, VAR_CONFIG, RESOURCE, TASK, PROGRAM or END_CONFIGURATION");
    }
  }
  expectEnd(Tok::KwEndConfiguration, "CONFIGURATION", keywordLoc);
  return config;
}

// VAR_CONFIG  p.x AT %IX1.0 : BOOL [:= init]; ...  END_VAR
void Parser::parseVarConfig(std::vector<ConfigVar>& out) {
  SourceLocation keywordLoc = cur().loc;
  advance();
  while (!at(Tok::KwEndVar) && !isHardStop(cur().kind) && !stopped_) {
    ConfigVar entry;
    entry.loc = cur().loc;
    size_t before = pos_;
    do {
      std::string part = expectName("an instance path such as p.x");
      if (part.empty()) break;
      entry.path.push_back(std::move(part));
    } while (accept(Tok::Dot));
    bool ok = !entry.path.empty() && expect(Tok::KwAt, "after the path of a VAR_CONFIG entry");
    if (ok && at(Tok::DirectAddress)) {
      entry.location = std::string(cur().text);
      advance();
    } else if (ok) {
      errorExpected("a direct address such as %IX1.0", "after AT");
      ok = false;
    }
    if (ok && expect(Tok::Colon, "after the address")) {
      entry.type = parseTypeSpec(false, nullptr);
      if (accept(Tok::Assign)) entry.init = parseExpr();
      if (expect(Tok::Semicolon, "after a VAR_CONFIG entry")) {
        out.push_back(std::move(entry));
        continue;
      }
    }
    skipPastSemicolon(false);
    if (pos_ == before) advance();
  }
  expectEnd(Tok::KwEndVar, "VAR_CONFIG", keywordLoc);
}

Resource Parser::parseResource() {
  Resource res;
  res.loc = cur().loc;
  SourceLocation keywordLoc = cur().loc;
  advance();
  res.name = expectName("a resource name", &res.loc);
  if (expect(Tok::KwOn, "after resource name")) res.onName = expectName("a processor type after ON");
  size_t lastStray = kNoStray;
  while (!at(Tok::KwEndResource) && !at(Tok::Eof) && !stopped_) {
    if (!parseResourceItem(res)) {
      if (at(Tok::KwEndConfiguration) || (isTopLevelStart(cur().kind) && !at(Tok::KwProgram))) break;
      skipStray(lastStray, "VAR_GLOBAL, TASK, PROGRAM or END_RESOURCE");
    }
  }
  expectEnd(Tok::KwEndResource, "RESOURCE", keywordLoc);
  return res;
}

// One VAR_GLOBAL block, TASK or PROGRAM of a resource; false if none starts here.
bool Parser::parseResourceItem(Resource& res) {
  if (at(Tok::KwVarGlobal)) {
    res.globals.push_back(parseVarBlock());
  } else if (at(Tok::KwTask)) {
    res.tasks.push_back(parseTask());
  } else if (at(Tok::KwProgram)) {
    res.programs.push_back(parseProgramConfig());
  } else {
    return false;
  }
  return true;
}

// TASK name (INTERVAL := T#10ms, PRIORITY := 1);
TaskDecl Parser::parseTask() {
  TaskDecl task;
  task.loc = cur().loc;
  advance();
  task.name = expectName("a task name", &task.loc);
  if (expect(Tok::LParen, "after task name")) parseCallArgs(task.settings);
  if (!expect(Tok::Semicolon, "after task declaration")) skipPastSemicolon(false);
  return task;
}

// PROGRAM instance [WITH task] : Type [(args)];
ProgramConfig Parser::parseProgramConfig() {
  ProgramConfig program;
  program.loc = cur().loc;
  advance();
  program.instanceName = expectName("a program instance name", &program.loc);
  if (accept(Tok::KwWith)) program.taskName = expectName("a task name after WITH");
  if (expect(Tok::Colon, "after program instance name")) program.typeName = parseQualifiedName();
  if (accept(Tok::LParen)) parseCallArgs(program.args);
  if (!expect(Tok::Semicolon, "after program configuration")) skipPastSemicolon(false);
  return program;
}

}  // namespace virtcom::st::detail
