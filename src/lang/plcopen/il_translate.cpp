// IL bodies to ST statements; the rules are in il_translate.hpp.
#include "lang/plcopen/il_translate.hpp"

#include <algorithm>
#include <optional>
#include <span>

#include "core/ascii.hpp"
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/jump_sections.hpp"
#include "lang/st/parse/parser.hpp"

namespace virtcom::plcopen::detail {

namespace {

enum class Kind : uint8_t { Label, Load, Store, Set, Reset, Not, Binary, Jump, Call, Return, Close, Function };
enum class Cond : uint8_t { Always, IfTrue, IfFalse };

struct Operator {
  std::string_view name;
  Kind kind;
  st::BinaryOp binary = st::BinaryOp::Add;
  bool negate = false;  // the N modifier: of the operand (LDN, ANDN), of the CR (STN)
  Cond cond = Cond::Always;
};

constexpr Operator kOperators[] = {
    {"LD", Kind::Load},        {"LDN", Kind::Load, st::BinaryOp::Add, true},
    {"ST", Kind::Store},       {"STN", Kind::Store, st::BinaryOp::Add, true},
    {"S", Kind::Set},          {"R", Kind::Reset},
    {"NOT", Kind::Not},
    {"AND", Kind::Binary, st::BinaryOp::And},  {"ANDN", Kind::Binary, st::BinaryOp::And, true},
    {"&", Kind::Binary, st::BinaryOp::And},    {"&N", Kind::Binary, st::BinaryOp::And, true},
    {"OR", Kind::Binary, st::BinaryOp::Or},    {"ORN", Kind::Binary, st::BinaryOp::Or, true},
    {"XOR", Kind::Binary, st::BinaryOp::Xor},  {"XORN", Kind::Binary, st::BinaryOp::Xor, true},
    {"ADD", Kind::Binary, st::BinaryOp::Add},  {"SUB", Kind::Binary, st::BinaryOp::Sub},
    {"MUL", Kind::Binary, st::BinaryOp::Mul},  {"DIV", Kind::Binary, st::BinaryOp::Div},
    {"MOD", Kind::Binary, st::BinaryOp::Mod},
    {"GT", Kind::Binary, st::BinaryOp::Gt},    {"GE", Kind::Binary, st::BinaryOp::Ge},
    {"EQ", Kind::Binary, st::BinaryOp::Eq},    {"NE", Kind::Binary, st::BinaryOp::Ne},
    {"LE", Kind::Binary, st::BinaryOp::Le},    {"LT", Kind::Binary, st::BinaryOp::Lt},
    {"JMP", Kind::Jump},       {"JMPC", Kind::Jump, st::BinaryOp::Add, false, Cond::IfTrue},
    {"JMPCN", Kind::Jump, st::BinaryOp::Add, false, Cond::IfFalse},
    {"CAL", Kind::Call},       {"CALC", Kind::Call, st::BinaryOp::Add, false, Cond::IfTrue},
    {"CALCN", Kind::Call, st::BinaryOp::Add, false, Cond::IfFalse},
    {"RET", Kind::Return},     {"RETC", Kind::Return, st::BinaryOp::Add, false, Cond::IfTrue},
    {"RETCN", Kind::Return, st::BinaryOp::Add, false, Cond::IfFalse},
    {")", Kind::Close},
};

// The FB input operators of IEC 61131-3: `CLK trig` calls trig(CLK := CR), as matiec reads them.
// S and R are ones too when their operand is an RS or SR instance (else they set/reset a BOOL).
constexpr std::string_view kFbInputOperators[] = {"S1", "R1", "CLK", "CU", "CD", "PV", "IN", "PT"};
constexpr std::string_view kSetResetFbs[] = {"RS", "SR"};

bool isOneOf(std::string_view upper, std::span<const std::string_view> names) {
  return std::find(names.begin(), names.end(), upper) != names.end();
}

bool isComparison(st::BinaryOp op) {
  return op == st::BinaryOp::Gt || op == st::BinaryOp::Ge || op == st::BinaryOp::Eq || op == st::BinaryOp::Ne ||
         op == st::BinaryOp::Le || op == st::BinaryOp::Lt;
}

struct Instruction {
  Operator op;
  std::string written;        // the operator as written (a function's name keeps its case)
  std::string_view operand;   // trimmed; for a label its name
  size_t operandOffset = 0;   // into the body text
  size_t offset = 0;          // of the operator (or label)
  bool opensParen = false;    // AND( ...
  bool formal = false;        // LIMIT( MN := 0, IN := x, MX := 5 ): a call with a formal argument list
};

bool isWordChar(char c) { return isAsciiLetter(c) || isAsciiDigit(c) || c == '_'; }

// The body text with every comment blanked out (same length, line breaks kept), so offsets into
// it are offsets into the XML text node.
std::string withoutComments(std::string_view text) {
  std::string out(text);
  for (size_t i = 0; i < out.size(); ++i) {
    if (out[i] == '\'' || out[i] == '"') {  // a string literal may hold "(*"
      char quote = out[i];
      for (++i; i < out.size() && out[i] != quote && out[i] != '\n'; ++i) {
        if (out[i] == '$') ++i;
      }
    } else if (out.compare(i, 2, "(*") == 0) {
      size_t end = out.find("*)", i + 2);
      end = end == std::string::npos ? out.size() : end + 2;
      for (; i < end; ++i)
        if (out[i] != '\n') out[i] = ' ';
      --i;
    } else if (out.compare(i, 2, "//") == 0) {
      for (; i < out.size() && out[i] != '\n'; ++i) out[i] = ' ';
    }
  }
  return out;
}

class IlTranslator {
 public:
  IlTranslator(Importer& imp, pugi::xml_node text, st::Pou& owner, std::string_view prefix)
      : imp_(imp), b_(imp.build()), textNode_(text), text_(text.value()), clean_(withoutComments(text_)),
        owner_(owner), prefix_(prefix) {
    temps_.section = prefix.empty() ? st::VarSection::Temp : st::VarSection::Var;
  }

  st::StmtList run();

 private:
  // ---- reading ----
  void read();
  size_t readLine(size_t pos, size_t end);
  size_t operandEnd(size_t pos, size_t lineEnd, bool call) const;
  bool formalList(size_t paren) const;
  SourceLocation at(size_t offset) const;
  void fail(std::string_view code, size_t offset, std::string message);

  // ---- translating ----
  void translate(const Instruction& ins, size_t index);
  st::ExprPtr operand(const Instruction& ins);
  void applyBinary(const Operator& op, st::ExprPtr rhs, std::string rhsType, SourceLocation loc);
  bool requireCr(const Instruction& ins);
  void holdAsBool(SourceLocation loc);
  void call(const Instruction& ins);
  void fbInput(const Instruction& ins, st::ExprPtr instance);
  void function(const Instruction& ins);
  static std::string conversionResult(std::string_view function);
  void jump(const Instruction& ins);
  st::StmtPtr carryTo(size_t label, SourceLocation loc);
  void startLabel(size_t label, SourceLocation loc);
  void emitGuarded(Cond cond, st::StmtList body, SourceLocation loc);
  std::string hidden(std::string name, std::string_view type, SourceLocation loc);
  std::string crVariable(const std::string& type, SourceLocation loc);
  std::string typeOf(const st::Expr& e) const;
  bool reads(const st::Expr& e, std::string_view name) const;
  bool needsCrAt(size_t label) const;

  Importer& imp_;
  AstBuilder& b_;
  pugi::xml_node textNode_;
  std::string_view text_;
  std::string clean_;
  st::Pou& owner_;
  std::string prefix_;
  std::vector<Instruction> code_;

  struct Label {
    std::string name;
    size_t index;            // of its Label instruction in code_
    std::string crType;      // the type of the CR it receives; empty: not decided yet
  };
  std::vector<Label> labels_;
  std::vector<st::StmtList> sections_{1};
  std::string jumpVar_;

  // The CR: an expression and, where known, its type ("" unknown). Null: undefined.
  st::ExprPtr cr_;
  std::string crType_;
  struct Deferred {
    Operator op;
    st::ExprPtr saved;
    std::string savedType;
  };
  std::vector<Deferred> deferred_;
  st::VarBlock temps_;
  bool reachable_ = true;  // false after an unconditional jump or return, until a label
  bool failed_ = false;
};

SourceLocation IlTranslator::at(size_t offset) const {
  ptrdiff_t base = textNode_.offset_debug();
  if (base < 0) return imp_.xml().at(textNode_);
  return imp_.xml().atOffset(static_cast<size_t>(base) + offset);
}

void IlTranslator::fail(std::string_view code, size_t offset, std::string message) {
  imp_.diags().error(code, at(offset), std::move(message));
  failed_ = true;
}

void IlTranslator::read() {
  for (size_t pos = 0; pos < clean_.size();) {
    size_t lineEnd = clean_.find('\n', pos);
    if (lineEnd == std::string::npos) lineEnd = clean_.size();
    pos = readLine(pos, lineEnd);
  }
}

// Where the operand starting at `pos` ends: the line's end, or for a call with an argument list
// the parenthesis closing it (which may be lines further).
size_t IlTranslator::operandEnd(size_t pos, size_t lineEnd, bool call) const {
  size_t paren = clean_.find('(', pos);
  if (!call || paren == std::string::npos || paren > lineEnd) return lineEnd;
  int depth = 0;
  for (size_t i = paren; i < clean_.size(); ++i) {
    if (clean_[i] == '(') ++depth;
    if (clean_[i] == ')' && --depth == 0) return i + 1;
  }
  return clean_.size();
}

// True when the parenthesis at `paren` opens a formal argument list (`:=` or `=>` directly inside
// it) rather than a deferred operand (`ADD( x`), whose IL instructions never hold those.
bool IlTranslator::formalList(size_t paren) const {
  int depth = 0;
  for (size_t i = paren; i + 1 < clean_.size(); ++i) {
    if (clean_[i] == '(') ++depth;
    if (clean_[i] == ')' && --depth == 0) return false;
    if (depth == 1 && ((clean_[i] == ':' && clean_[i + 1] == '=') || (clean_[i] == '=' && clean_[i + 1] == '>'))) return true;
  }
  return false;
}

// Reads the label and instruction of the line [pos, lineEnd); returns where reading goes on.
size_t IlTranslator::readLine(size_t pos, size_t lineEnd) {
  auto skipBlanks = [&](size_t i) {
    while (i < lineEnd && isAsciiSpace(clean_[i])) ++i;
    return i;
  };
  size_t i = skipBlanks(pos);
  size_t wordEnd = i;
  while (wordEnd < lineEnd && isWordChar(clean_[wordEnd])) ++wordEnd;
  size_t afterWord = skipBlanks(wordEnd);
  if (wordEnd > i && afterWord < lineEnd && clean_[afterWord] == ':' &&
      (afterWord + 1 >= lineEnd || clean_[afterWord + 1] != '=')) {
    Instruction label;
    label.op = {"", Kind::Label};
    label.operand = std::string_view(text_).substr(i, wordEnd - i);
    label.offset = i;
    code_.push_back(label);
    i = skipBlanks(afterWord + 1);
    wordEnd = i;
    while (wordEnd < lineEnd && isWordChar(clean_[wordEnd])) ++wordEnd;
  }
  if (i >= lineEnd) return lineEnd + 1;
  Instruction ins;
  ins.offset = i;
  if (clean_[i] == ')') {
    wordEnd = i + 1;
  } else if (clean_[i] == '&') {
    wordEnd = i + 1;
    if (wordEnd < lineEnd && (clean_[wordEnd] == 'N' || clean_[wordEnd] == 'n')) ++wordEnd;
  } else if (wordEnd == i) {
    fail(diag::X011, i, "IL: expected an operator or a label, found '" + std::string(1, clean_[i]) + "'");
    return lineEnd + 1;
  }
  ins.written = std::string(text_.substr(i, wordEnd - i));
  std::string upper = asciiUpper(ins.written);
  auto known = std::find_if(std::begin(kOperators), std::end(kOperators), [&](const Operator& o) { return o.name == upper; });
  ins.op = known != std::end(kOperators) ? *known : Operator{"", Kind::Function};
  size_t rest = skipBlanks(wordEnd);
  if (rest < lineEnd && clean_[rest] == '(' && (ins.op.kind == Kind::Binary || ins.op.kind == Kind::Function) &&
      formalList(rest)) {
    ins.op = Operator{"", Kind::Function};  // `ADD( IN1 := a, IN2 := b )` calls ADD
    ins.formal = true;
  } else if (rest < lineEnd && clean_[rest] == '(' && (ins.op.kind == Kind::Binary)) {
    ins.opensParen = true;
    rest = skipBlanks(rest + 1);
  }
  size_t end = operandEnd(rest, lineEnd, ins.op.kind == Kind::Call || ins.formal);
  std::string_view operand = trimAscii(std::string_view(clean_).substr(rest, end - rest));
  ins.operandOffset = operand.empty() ? rest : static_cast<size_t>(operand.data() - clean_.data());
  ins.operand = std::string_view(text_).substr(ins.operandOffset, operand.size());
  code_.push_back(ins);
  if (end > lineEnd) {  // an argument list over several lines: the rest of its last line
    size_t lastLineEnd = clean_.find('\n', end);
    if (lastLineEnd == std::string::npos) lastLineEnd = clean_.size();
    if (!trimAscii(std::string_view(clean_).substr(end, lastLineEnd - end)).empty())
      fail(diag::X011, end, "IL: one instruction per line; text follows the call's ')'");
    return lastLineEnd + 1;
  }
  return lineEnd + 1;
}

st::ExprPtr IlTranslator::operand(const Instruction& ins) {
  if (ins.operand.empty()) {
    fail(diag::X011, ins.offset, "IL: " + ins.written + " needs an operand");
    return nullptr;
  }
  return st::parseExpression(imp_.xml().fileId(), at(ins.operandOffset), ins.operand, imp_.diags(), imp_.nextNodeId());
}

// The declared type of a variable of the POU or of a named global list, a typed literal's
// type, BOOL for TRUE/FALSE; "" when it does not follow from the operand alone.
std::string IlTranslator::typeOf(const st::Expr& e) const {
  switch (e.kind) {
    case st::ExprKind::BoolLit: return "BOOL";
    case st::ExprKind::IntLit: case st::ExprKind::RealLit: case st::ExprKind::TimeLit: case st::ExprKind::DateLit:
      return e.typePrefix;
    case st::ExprKind::Name: break;
    default: return "";
  }
  auto declared = [&](const std::vector<st::VarBlock>& blocks) -> std::string {
    for (const st::VarBlock& block : blocks)
      for (const st::VarDecl& decl : block.vars)
        for (const st::DeclName& n : decl.names)
          if (iequalsAscii(n.name, e.text) && decl.type.kind == st::TypeSpecKind::Named) return decl.type.name;
    return "";
  };
  if (std::string t = declared(owner_.varBlocks); !t.empty()) return t;
  for (const st::GlobalVarList& gvl : imp_.unit().globals)
    if (std::string t = declared(gvl.blocks); !t.empty()) return t;
  return "";
}

bool IlTranslator::reads(const st::Expr& e, std::string_view name) const {
  if (e.kind == st::ExprKind::Name && iequalsAscii(e.text, name)) return true;
  if (e.lhs && reads(*e.lhs, name)) return true;
  if (e.rhs && reads(*e.rhs, name)) return true;
  for (const st::ExprPtr& item : e.items)
    if (item && reads(*item, name)) return true;
  for (const st::CallArg& arg : e.args)
    if (arg.value && reads(*arg.value, name)) return true;
  return false;
}

// A hidden variable of the body, declared the first time it is asked for.
std::string IlTranslator::hidden(std::string name, std::string_view type, SourceLocation loc) {
  bool declared = std::any_of(temps_.vars.begin(), temps_.vars.end(),
                              [&](const st::VarDecl& d) { return d.names.front().name == name; });
  if (!declared) {
    st::VarDecl decl;
    decl.names.push_back({name, loc});
    decl.type.name = std::string(type);
    decl.type.loc = loc;
    decl.loc = loc;
    temps_.vars.push_back(std::move(decl));
  }
  return name;
}

std::string IlTranslator::crVariable(const std::string& type, SourceLocation loc) {
  return hidden("__" + prefix_ + "il_cr_" + type, type, loc);
}

bool IlTranslator::requireCr(const Instruction& ins) {
  if (cr_) return true;
  fail(diag::X011, ins.offset, "IL: " + ins.written + " reads the current result, which no instruction has set here "
                                                       "(load one with LD first)");
  return false;
}

// Instructions that take the CR as a BOOL and must evaluate it once hold it in a hidden BOOL.
void IlTranslator::holdAsBool(SourceLocation loc) {
  if (cr_->kind == st::ExprKind::Name || cr_->kind == st::ExprKind::BoolLit) return;
  std::string var = crVariable("BOOL", loc);
  sections_.back().push_back(b_.assign(b_.name(var, loc), std::move(cr_)));
  cr_ = b_.name(var, loc);
  crType_ = "BOOL";
}

void IlTranslator::emitGuarded(Cond cond, st::StmtList body, SourceLocation loc) {
  if (cond == Cond::Always) {
    for (auto& s : body) sections_.back().push_back(std::move(s));
    return;
  }
  st::ExprPtr test = b_.clone(*cr_);
  if (cond == Cond::IfFalse) test = b_.notOf(std::move(test));
  test->loc = loc;
  sections_.back().push_back(b_.ifThen(std::move(test), std::move(body)));
}

void IlTranslator::applyBinary(const Operator& op, st::ExprPtr rhs, std::string rhsType, SourceLocation loc) {
  if (op.negate) rhs = b_.notOf(std::move(rhs));
  cr_ = b_.binary(op.binary, std::move(cr_), std::move(rhs));
  cr_->loc = loc;
  if (isComparison(op.binary)) crType_ = "BOOL";
  else if (crType_.empty()) crType_ = std::move(rhsType);
}

bool IlTranslator::needsCrAt(size_t label) const {
  for (size_t k = labels_[label].index + 1; k < code_.size(); ++k) {
    const Operator& op = code_[k].op;
    if (op.kind == Kind::Label) continue;
    bool setsCr = op.kind == Kind::Load ||
                  (op.cond == Cond::Always && (op.kind == Kind::Jump || op.kind == Kind::Return || op.kind == Kind::Call));
    return !setsCr;
  }
  return false;
}

// The assignment handing the CR to `label` (jumping or falling through to it), or null when its
// first instruction does not read one.
st::StmtPtr IlTranslator::carryTo(size_t label, SourceLocation loc) {
  if (!needsCrAt(label)) return nullptr;
  Label& target = labels_[label];
  if (!cr_) {
    fail(diag::X011, code_[target.index].offset,
         "IL: label '" + target.name + "' is reached without a current result, but its first instruction reads one");
    return nullptr;
  }
  if (target.crType.empty()) target.crType = crType_;
  if (target.crType.empty()) {
    fail(diag::X011, code_[target.index].offset,
         "IL: the current result carried to label '" + target.name + "' has a type that does not follow from its "
         "operands; load a declared variable or a typed literal (e.g. INT#1) before the jump");
    return nullptr;
  }
  if (!crType_.empty() && !iequalsAscii(crType_, target.crType)) {
    fail(diag::X011, code_[target.index].offset,
         "IL: label '" + target.name + "' is reached with current results of types " + target.crType + " and " + crType_);
    return nullptr;
  }
  return b_.assign(b_.name(crVariable(target.crType, loc), loc), b_.clone(*cr_));
}

void IlTranslator::startLabel(size_t label, SourceLocation loc) {
  if (!deferred_.empty()) fail(diag::X011, code_[labels_[label].index].offset, "IL: a label inside parentheses");
  if (reachable_)  // falling through
    if (st::StmtPtr carry = carryTo(label, loc)) sections_.back().push_back(std::move(carry));
  reachable_ = true;
  sections_.emplace_back();
  if (needsCrAt(label) && !labels_[label].crType.empty()) {
    cr_ = b_.name(crVariable(labels_[label].crType, loc), loc);
    crType_ = labels_[label].crType;
  } else {
    cr_.reset();
    crType_.clear();
  }
}

void IlTranslator::jump(const Instruction& ins) {
  SourceLocation loc = at(ins.offset);
  auto label = std::find_if(labels_.begin(), labels_.end(), [&](const Label& l) { return iequalsAscii(l.name, ins.operand); });
  if (label == labels_.end()) {
    fail(diag::X010, ins.operandOffset, "IL: there is no label '" + std::string(ins.operand) + "' in this body");
    return;
  }
  if (ins.op.cond != Cond::Always) {
    if (!requireCr(ins)) return;
    holdAsBool(loc);
  }
  size_t index = static_cast<size_t>(label - labels_.begin());
  if (jumpVar_.empty()) jumpVar_ = hidden("__" + prefix_ + "il_jump", "INT", loc);
  st::StmtList body;
  if (st::StmtPtr carry = carryTo(index, loc)) body.push_back(std::move(carry));
  for (st::StmtPtr& s : jumpToSection(b_, jumpVar_, index + 1, loc)) body.push_back(std::move(s));
  emitGuarded(ins.op.cond, std::move(body), loc);
  if (ins.op.cond == Cond::Always) reachable_ = false;  // what follows is reached only through a label
}

void IlTranslator::call(const Instruction& ins) {
  SourceLocation loc = at(ins.offset);
  st::ExprPtr target = operand(ins);
  if (!target) return;
  if (target->kind != st::ExprKind::Call) {
    st::ExprPtr c = b_.expr(st::ExprKind::Call, target->loc);
    c->lhs = std::move(target);
    target = std::move(c);
  }
  if (ins.op.cond != Cond::Always) {
    if (!requireCr(ins)) return;
    holdAsBool(loc);
  }
  const st::Expr* callee = target->lhs.get();
  while (callee && callee->kind != st::ExprKind::Name && callee->lhs) callee = callee->lhs.get();
  std::string instance = callee ? callee->text : "";
  st::StmtList body;
  body.push_back(b_.callStmt(std::move(target)));
  emitGuarded(ins.op.cond, std::move(body), loc);
  if (cr_ && reads(*cr_, instance)) cr_.reset();
}

// `CLK trig`: trig(CLK := CR); the CR stays unless it reads the instance's outputs.
void IlTranslator::fbInput(const Instruction& ins, st::ExprPtr instance) {
  if (!requireCr(ins)) return;
  SourceLocation loc = at(ins.offset);
  const std::string name = instance->kind == st::ExprKind::Name ? instance->text : std::string();
  st::ExprPtr c = b_.expr(st::ExprKind::Call, loc);
  c->lhs = std::move(instance);
  st::CallArg input;
  input.name = asciiUpper(ins.written);
  input.loc = loc;
  input.value = b_.clone(*cr_);
  c->args.push_back(std::move(input));
  sections_.back().push_back(b_.callStmt(std::move(c)));
  if (reads(*cr_, name)) cr_.reset();
}

// The type a conversion function `X_TO_Y` gives (Y); "" for other functions.
std::string IlTranslator::conversionResult(std::string_view function) {
  size_t to = asciiUpper(function).find("_TO_");
  return to == std::string::npos ? "" : asciiUpper(function.substr(to + 4));
}

void IlTranslator::function(const Instruction& ins) {
  if (isOneOf(asciiUpper(ins.written), kFbInputOperators)) {
    if (st::ExprPtr instance = operand(ins)) fbInput(ins, std::move(instance));
    return;
  }
  if (ins.formal) {
    // IEC's formal call: the call as written; its result replaces the CR, which it does not read.
    std::string_view call = std::string_view(clean_).substr(ins.offset, ins.operandOffset + ins.operand.size() - ins.offset);
    cr_ = st::parseExpression(imp_.xml().fileId(), at(ins.offset), call, imp_.diags(), imp_.nextNodeId());
    crType_ = conversionResult(ins.written);
    return;
  }
  if (!requireCr(ins)) return;
  SourceLocation loc = at(ins.offset);
  st::ExprPtr c = b_.expr(st::ExprKind::Call, loc);
  c->lhs = b_.name(ins.written, loc);
  st::CallArg first;
  first.loc = loc;
  first.value = std::move(cr_);
  c->args.push_back(std::move(first));
  // Further arguments: the operand split at its top-level commas.
  size_t start = 0;
  int depth = 0;
  for (size_t k = 0; k <= ins.operand.size() && !ins.operand.empty(); ++k) {
    char ch = k < ins.operand.size() ? ins.operand[k] : ',';
    if (ch == '(' || ch == '[') ++depth;
    if (ch == ')' || ch == ']') --depth;
    if (ch != ',' || depth > 0) continue;
    std::string_view piece = trimAscii(ins.operand.substr(start, k - start));
    st::CallArg arg;
    arg.loc = at(ins.operandOffset + static_cast<size_t>(piece.data() - ins.operand.data()));
    arg.value = st::parseExpression(imp_.xml().fileId(), arg.loc, piece, imp_.diags(), imp_.nextNodeId());
    c->args.push_back(std::move(arg));
    start = k + 1;
  }
  cr_ = std::move(c);
  crType_ = conversionResult(ins.written);
}

void IlTranslator::translate(const Instruction& ins, size_t index) {
  SourceLocation loc = at(ins.offset);
  const Operator& op = ins.op;
  switch (op.kind) {
    case Kind::Label: {
      auto label = std::find_if(labels_.begin(), labels_.end(), [&](const Label& l) { return l.index == index; });
      startLabel(static_cast<size_t>(label - labels_.begin()), loc);
      break;
    }
    case Kind::Load: {
      st::ExprPtr value = operand(ins);
      if (!value) break;
      crType_ = typeOf(*value);
      cr_ = op.negate ? b_.notOf(std::move(value)) : std::move(value);
      break;
    }
    case Kind::Store: {
      st::ExprPtr target = operand(ins);
      if (!target || !requireCr(ins)) break;
      st::ExprPtr value = op.negate ? b_.notOf(b_.clone(*cr_)) : b_.clone(*cr_);
      sections_.back().push_back(b_.assign(b_.clone(*target), std::move(value)));
      if (!op.negate) {  // the CR is now what the variable holds
        if (std::string t = typeOf(*target); !t.empty()) crType_ = t;
        cr_ = std::move(target);
      }
      break;
    }
    case Kind::Set: case Kind::Reset: {
      st::ExprPtr target = operand(ins);
      if (target && isOneOf(asciiUpper(typeOf(*target)), kSetResetFbs)) {
        fbInput(ins, std::move(target));
        break;
      }
      if (!target || !requireCr(ins)) break;
      if (reads(*cr_, target->kind == st::ExprKind::Name ? target->text : std::string())) {
        std::string var = crVariable("BOOL", loc);
        sections_.back().push_back(b_.assign(b_.name(var, loc), std::move(cr_)));
        cr_ = b_.name(var, loc);
      } else {
        holdAsBool(loc);
      }
      sections_.back().push_back(
          b_.assign(std::move(target), b_.clone(*cr_), op.kind == Kind::Set ? st::StmtKind::SetAssign : st::StmtKind::ResetAssign));
      break;
    }
    case Kind::Not:
      if (!requireCr(ins)) break;
      cr_ = b_.notOf(std::move(cr_));
      break;
    case Kind::Binary: {
      if (!requireCr(ins)) break;
      if (ins.opensParen) {
        deferred_.push_back({op, std::move(cr_), crType_});
        crType_.clear();
        if (!ins.operand.empty())
          if (st::ExprPtr first = operand(ins)) {
            crType_ = typeOf(*first);
            cr_ = std::move(first);
          }
        break;
      }
      st::ExprPtr rhs = operand(ins);
      if (!rhs) break;
      std::string rhsType = typeOf(*rhs);
      applyBinary(op, std::move(rhs), std::move(rhsType), loc);
      break;
    }
    case Kind::Close: {
      if (deferred_.empty()) {
        fail(diag::X011, ins.offset, "IL: ')' without a deferred operator such as AND(");
        break;
      }
      Deferred d = std::move(deferred_.back());
      deferred_.pop_back();
      if (!requireCr(ins)) break;
      st::ExprPtr inner = std::move(cr_);
      std::string innerType = std::move(crType_);
      cr_ = std::move(d.saved);
      crType_ = std::move(d.savedType);
      applyBinary(d.op, std::move(inner), std::move(innerType), loc);
      break;
    }
    case Kind::Jump: jump(ins); break;
    case Kind::Call: call(ins); break;
    case Kind::Return: {
      if (op.cond != Cond::Always) {
        if (!requireCr(ins)) break;
        holdAsBool(loc);
      }
      st::StmtList body;
      body.push_back(b_.simple(st::StmtKind::Return, loc));
      emitGuarded(op.cond, std::move(body), loc);
      if (op.cond == Cond::Always) reachable_ = false;
      break;
    }
    case Kind::Function: function(ins); break;
  }
}

st::StmtList IlTranslator::run() {
  read();
  for (size_t k = 0; k < code_.size(); ++k) {
    if (code_[k].op.kind != Kind::Label) continue;
    std::string name(code_[k].operand);
    if (std::any_of(labels_.begin(), labels_.end(), [&](const Label& l) { return iequalsAscii(l.name, name); }))
      fail(diag::X011, code_[k].offset, "IL: label '" + name + "' is defined twice");
    labels_.push_back({name, k, ""});
  }
  for (size_t k = 0; k < code_.size() && !failed_; ++k) translate(code_[k], k);
  if (!deferred_.empty() && !failed_) fail(diag::X011, clean_.size(), "IL: a deferred operator's ')' is missing");
  st::StmtList body = joinSections(b_, std::move(sections_), jumpVar_, at(0));
  if (!temps_.vars.empty()) owner_.varBlocks.push_back(std::move(temps_));
  return body;
}

}  // namespace

st::StmtList translateIl(Importer& imp, pugi::xml_node text, st::Pou& owner, std::string_view prefix) {
  return IlTranslator(imp, text, owner, prefix).run();
}

}  // namespace virtcom::plcopen::detail
