#pragma once
// Internal to the ST parser: the recursive-descent Parser whose methods are spread over
// parser.cpp (tokens, recovery, top level), parser_pous.cpp (POUs, interfaces, configurations),
// parser_decls.cpp (variables, types), parser_stmts.cpp and parser_exprs.cpp.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/sfc/sfc_model.hpp"
#include "lang/syntax/ast.hpp"
#include "lang/syntax/token.hpp"

namespace virtcom::st::detail {

// Bound on the syntax tree's height. Each nested construct (parenthesis, unary operator,
// statement, type) costs kRecursionCost and each binary operator of a chain costs 1, so both
// parser recursion (stack) and tree height (recursive destruction, later passes) stay bounded.
inline constexpr int kMaxNesting = 1024;
inline constexpr int kRecursionCost = 4;

class Parser {
 public:
  Parser(uint32_t fileId, std::vector<Token> tokens, Diagnostics& diags, NodeId& nextNodeId);
  CompilationUnit parseUnit();
  StmtList parseStatementFragment();   // statements up to the end of the tokens
  ExprPtr parseExpressionFragment();   // exactly one expression

 private:
  // ---- tokens (parser.cpp) ----
  const Token& cur() const { return toks_[pos_]; }
  const Token& peekTok(size_t ahead) const;
  bool at(Tok kind) const { return cur().kind == kind; }
  bool accept(Tok kind);
  void advance();
  static bool isNameToken(Tok kind);  // identifiers and context keywords (GET, SET, ON, ...)
  bool atName() const { return isNameToken(cur().kind); }
  bool expect(Tok kind, std::string_view context);
  std::string expectName(std::string_view what, SourceLocation* loc = nullptr);
  bool expectEnd(Tok endKind, std::string_view opener, SourceLocation openLoc, SourceLocation* endLoc = nullptr);

  // ---- diagnostics and recovery (parser.cpp) ----
  void error(std::string_view code, std::string message);  // at the current token
  void errorExpected(std::string_view expected, std::string_view context);
  static std::string describe(const Token& tok);
  static bool isTopLevelStart(Tok kind);
  static bool isPouEnd(Tok kind);
  static bool isVarBlockStart(Tok kind);
  static bool isSoftEnd(Tok kind);  // END_IF, ELSE, UNTIL, ...
  bool isHardStop(Tok kind) const;  // ends any statement list / declaration list
  void skipToTopLevel();
  void skipPastSemicolon(bool stopAtStatementStart);
  // Reports the current token as unexpected and skips it; a run of consecutive stray tokens gets
  // one error, not one per token. `lastStray` (initially kNoStray) is the loop's memory of it.
  static constexpr size_t kNoStray = static_cast<size_t>(-2);
  void skipStray(size_t& lastStray, std::string_view expected);
  void stopParsing(std::string message);  // nesting too deep: report once, jump to Eof
  std::vector<Attribute> takeAttributes();

  struct NestingGuard {
    Parser& p;
    int cost;
    bool ok;
    NestingGuard(Parser& parser, int c);
    ~NestingGuard() { p.depth_ -= cost; }
    NestingGuard(const NestingGuard&) = delete;
    NestingGuard& operator=(const NestingGuard&) = delete;
  };
  // Marks the end keywords (END_IF, ELSE, ...) that an enclosing construct is waiting for, so an
  // inner statement list stops at them instead of skipping them as strays.
  struct OpenConstruct {
    Parser& p;
    std::vector<Tok> ends;
    OpenConstruct(Parser& parser, std::initializer_list<Tok> kinds);
    ~OpenConstruct();
  };

  ExprPtr makeExpr(ExprKind kind, SourceLocation loc);
  StmtPtr makeStmt(StmtKind kind, SourceLocation loc);
  ExprPtr errorExpr(SourceLocation loc) { return makeExpr(ExprKind::Name, loc); }

  // ---- POUs (parser_pous.cpp) ----
  std::unique_ptr<Pou> parsePou(std::vector<Attribute> attributes);
  void parsePouHeaderModifiers(Pou& pou);
  void parseInheritance(Pou& pou);
  void parsePouBody(Pou& pou, Tok endKind, bool allowMembers);
  void parseVarBlocks(std::vector<VarBlock>& blocks);
  std::unique_ptr<Pou> parseMethod(bool inInterface, std::vector<Attribute> attributes);
  Property parseProperty(bool inInterface);
  std::unique_ptr<Pou> parseAccessor(const Property& prop, bool getter, bool noBody);
  std::unique_ptr<Pou> parseAction(std::vector<Attribute> attributes);
  Interface parseInterface();
  void parseModifiers(Access& access, bool& isAbstract, bool& isFinal);
  Configuration parseConfiguration();
  Resource parseResource();
  void parseVarConfig(std::vector<ConfigVar>& out);
  bool parseResourceItem(Resource& res);
  TaskDecl parseTask();
  ProgramConfig parseProgramConfig();

  // ---- declarations (parser_decls.cpp) ----
  VarBlock parseVarBlock();
  bool parseVarDecl(VarDecl& decl, bool allowLocation);
  void parseDeclNames(std::vector<DeclName>& names);
  TypeSpec parseTypeSpec(bool allowStruct, std::vector<CallArg>* fbInitArgs);
  void parseNamedTypeSuffix(TypeSpec& spec, std::vector<CallArg>* fbInitArgs);
  void parseStringType(TypeSpec& spec);
  void parseArrayType(TypeSpec& spec);
  void parseEnumType(TypeSpec& spec);
  void parseStructType(TypeSpec& spec);
  void parseTypeBlock(std::vector<TypeDecl>& out, std::vector<Attribute> attributes);
  std::string parseQualifiedName();
  void addGlobalBlock(CompilationUnit& unit, std::vector<Attribute> attributes);

  // ---- textual SFC (parser_sfc.cpp) ----
  // INITIAL_STEP, STEP, TRANSITION, FROM, PRIORITY, END_STEP and END_TRANSITION are context
  // keywords (plain identifiers elsewhere), so programs with a variable `step` still compile.
  bool atSfcElement() const;  // INITIAL_STEP / STEP name : / TRANSITION ... FROM
  bool atSfcEnd() const;      // END_STEP / END_TRANSITION
  void parseSfcElement(sfc::Chart& chart);
  sfc::Step parseStep();
  bool parseActionAssociation(sfc::Step& step);
  sfc::Transition parseTransition();
  void parseStepNames(std::vector<sfc::NamedRef>& out, std::string_view context);
  void finishChart(sfc::Chart& chart, Pou& pou, size_t errorsBefore);

  // ---- statements (parser_stmts.cpp) ----
  StmtList parseStatementList(std::initializer_list<Tok> ends, bool inCaseBranch = false);
  bool endsStatementList(std::initializer_list<Tok> ends, bool inCaseBranch);
  StmtPtr parseStatement();
  StmtPtr parseAssignmentOrCall();
  StmtPtr parseIf();
  StmtPtr parseCase();
  bool parseCaseBranch(CaseBranch& branch);
  StmtPtr parseFor();
  StmtPtr parseWhile();
  StmtPtr parseRepeat();
  StmtPtr parseSimple(StmtKind kind);
  bool atLabel() const;
  StmtPtr parseLabel();
  bool atJump() const;
  StmtPtr parseJump();
  void expectStatementEnd();
  bool looksLikeCaseLabel() const;
  bool atSetResetOperator() const;
  static bool isStatementStart(Tok kind);

  // ---- expressions (parser_exprs.cpp) ----
  ExprPtr parseExpr();
  ExprPtr parseBinary(int minPrecedence);
  ExprPtr parseUnary();
  ExprPtr parseNotParen();
  ExprPtr parsePostfix();
  ExprPtr parsePostfixOps(ExprPtr base);
  ExprPtr parsePrimary();
  ExprPtr parseMemberOrBit(ExprPtr base);
  ExprPtr parseTypedLiteral();
  ExprPtr parseArrayInit();
  ExprPtr parseStructInit();
  ExprPtr parseLiteralToken();
  bool atStructInit() const;
  void parseCallArgs(std::vector<CallArg>& args);  // after '(' up to and including ')'
  CallArg parseCallArg();

  uint32_t fileId_;
  std::vector<Token> toks_;
  size_t pos_ = 0;
  Diagnostics& diags_;
  NodeId& nextNodeId_;
  int depth_ = 0;
  bool stopped_ = false;
  size_t lastErrorPos_ = static_cast<size_t>(-1);
  // Attribute pragmas, keyed by the index of the token they precede.
  std::vector<std::pair<size_t, Attribute>> attributes_;
  size_t nextAttribute_ = 0;
  std::array<uint16_t, static_cast<size_t>(Tok::Count_)> openEnds_{};
};

}  // namespace virtcom::st::detail
