// Scenario conditions: a recursive-descent parser into a postfix program, and its evaluation.
#include "scenario/expression.hpp"

#include <bit>
#include <cstdlib>
#include <sstream>

#include "core/ascii.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "core/value_codec.hpp"

namespace virtcom::scenario {

namespace {

bool isNameChar(char c) { return isAsciiLetter(c) || isAsciiDigit(c) || c == '_' || c == '.' || c == '%'; }

struct Comparison {
  std::string_view symbol;
  Expression::OpKind kind;
};
// Longest symbols first, so `<=` is not read as `<`.
constexpr Comparison kComparisons[] = {
    {"<>", Expression::OpKind::Ne}, {"<=", Expression::OpKind::Le}, {">=", Expression::OpKind::Ge},
    {"==", Expression::OpKind::Eq}, {"!=", Expression::OpKind::Ne}, {"=", Expression::OpKind::Eq},
    {"<", Expression::OpKind::Lt},  {">", Expression::OpKind::Gt},
};

}  // namespace

class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, SourceLocation loc, const NameScope& scope, Diagnostics& diags)
      : text_(text), loc_(loc), scope_(scope), diags_(diags) {}

  Expression parse() {
    out_.text_ = text_;
    parseOr();
    skipSpaces();
    if (ok_ && pos_ < text_.size()) fail("unexpected '" + text_.substr(pos_) + "' (expected AND, OR, XOR or the end)");
    if (ok_ && static_cast<size_t>(maxDepth_) > Expression::kMaxDepth)
      fail("the condition nests too deeply (more than " + std::to_string(Expression::kMaxDepth) + " operands pending)");
    if (!ok_) out_.code_.clear();
    return std::move(out_);
  }

 private:
  void fail(const std::string& message) {
    if (!ok_) return;  // the first mistake only: the rest follows from it
    ok_ = false;
    SourceLocation at = loc_;
    at.col += static_cast<uint32_t>(pos_);
    diags_.error(celldiag::C061, at, "condition '" + text_ + "': " + message);
  }
  void skipSpaces() {
    while (pos_ < text_.size() && isAsciiSpace(text_[pos_])) ++pos_;
  }
  // The keyword at the cursor (a whole word, any case), consumed if present.
  bool keyword(std::string_view word) {
    skipSpaces();
    if (!istartsWithAscii(std::string_view(text_).substr(pos_), word)) return false;
    size_t end = pos_ + word.size();
    if (end < text_.size() && isNameChar(text_[end])) return false;
    pos_ = end;
    return true;
  }
  void emit(Expression::OpKind kind, int stackChange, uint32_t operand = 0, double value = 0) {
    out_.code_.push_back({kind, operand, value});
    depth_ += stackChange;
    maxDepth_ = std::max(maxDepth_, depth_);
  }

  void parseOr() {
    parseXor();
    while (ok_ && keyword("OR")) {
      parseXor();
      emit(Expression::OpKind::Or, -1);
    }
  }
  void parseXor() {
    parseAnd();
    while (ok_ && keyword("XOR")) {
      parseAnd();
      emit(Expression::OpKind::Xor, -1);
    }
  }
  void parseAnd() {
    parseUnary();
    while (ok_ && keyword("AND")) {
      parseUnary();
      emit(Expression::OpKind::And, -1);
    }
  }
  void parseUnary() {
    if (keyword("NOT")) {
      parseUnary();
      emit(Expression::OpKind::Not, 0);
      return;
    }
    parseCompare();
  }
  void parseCompare() {
    parseOperand();
    skipSpaces();
    for (const Comparison& c : kComparisons) {
      if (std::string_view(text_).substr(pos_, c.symbol.size()) != c.symbol) continue;
      pos_ += c.symbol.size();
      parseOperand();
      emit(c.kind, -1);
      return;
    }
  }
  void parseOperand() {
    if (!ok_) return;
    skipSpaces();
    if (pos_ >= text_.size()) return fail("a value or a name is missing at the end");
    const char c = text_[pos_];
    if (c == '(') {
      ++pos_;
      parseOr();
      skipSpaces();
      if (ok_ && (pos_ >= text_.size() || text_[pos_] != ')')) return fail("')' expected");
      ++pos_;
      return;
    }
    if (keyword("TRUE")) return emit(Expression::OpKind::Const, 1, 0, 1);
    if (keyword("FALSE")) return emit(Expression::OpKind::Const, 1, 0, 0);
    if (isAsciiDigit(c) || c == '-' || c == '+') {
      const char* begin = text_.c_str() + pos_;
      char* end = nullptr;
      double value = std::strtod(begin, &end);
      if (end == begin) return fail("a number or a name expected");
      pos_ += static_cast<size_t>(end - begin);
      return emit(Expression::OpKind::Const, 1, 0, value);
    }
    if (!isNameChar(c)) return fail(std::string("unexpected '") + c + "' (expected a name, a number, TRUE, FALSE, NOT or '(')");
    parseName();
  }
  // A name, with a bracketed index anywhere in it (MAIN.errorIn[3]): resolved here, once.
  void parseName() {
    const size_t start = pos_;
    for (int depth = 0; pos_ < text_.size(); ++pos_) {
      const char ch = text_[pos_];
      if (ch == '[') ++depth;
      else if (ch == ']') --depth;
      else if (depth == 0 && !isNameChar(ch)) break;
    }
    const std::string name = text_.substr(start, pos_ - start);
    Expression::Operand operand{name};
    Expression::OpKind kind = Expression::OpKind::Tag;
    if (TagId tag = scope_.bus ? scope_.bus->find(name) : kNoTag; tag != kNoTag) {
      operand.address = tag;
      operand.type = scope_.bus->type(tag);
    } else if (istartsWithAscii(name, "world.")) {
      kind = Expression::OpKind::Fact;
      if (!findFact(name.substr(6), operand.address)) {
        pos_ = start;
        return fail("the cell has no world fact '" + name.substr(6) + "'");
      }
    } else {
      kind = Expression::OpKind::Var;
      if (!resolveVariable(name, start, operand)) return;
    }
    out_.operands_.push_back(std::move(operand));
    emit(kind, 1, static_cast<uint32_t>(out_.operands_.size() - 1));
  }
  bool findFact(const std::string& name, uint32_t& id) const {
    if (!scope_.world) return false;
    for (size_t i = 0; i < scope_.world->factCount(); ++i)
      if (scope_.world->factName(static_cast<uint32_t>(i)) == name) {
        id = static_cast<uint32_t>(i);
        return true;
      }
    return false;
  }
  bool resolveVariable(const std::string& name, size_t start, Expression::Operand& operand) {
    auto ref = scope_.module ? bc::resolveVariable(*scope_.module, name) : std::nullopt;
    pos_ = start;
    if (!ref) {
      fail("'" + name + "' is neither a device signal (e.g. Robot1.busy), a world fact (world.NAME) nor a variable of the PLC");
      return false;
    }
    const bc::TypeDesc& t = scope_.module->types[ref->type];
    if (t.kind != bc::TypeKind::Elementary && t.kind != bc::TypeKind::Enum) {
      fail("'" + name + "' is a " + t.name + ", not an elementary variable");
      return false;
    }
    pos_ = start + name.size();
    operand.address = ref->address;
    operand.bit = ref->bit;
    operand.type = t.elem;
    return true;
  }

  const std::string& text_;
  SourceLocation loc_;
  const NameScope& scope_;
  Diagnostics& diags_;
  Expression out_;
  size_t pos_ = 0;
  int depth_ = 0, maxDepth_ = 0;
  bool ok_ = true;
};

Expression Expression::parse(const std::string& text, SourceLocation loc, const NameScope& scope, Diagnostics& diags) {
  return ExpressionParser(text, loc, scope, diags).parse();
}

double Expression::load(const Operand& o, OpKind kind, const ValueSources& in) const {
  switch (kind) {
    case OpKind::Tag: {
      const uint64_t raw = in.bus->raw(o.address);
      if (isFloat(o.type)) return std::bit_cast<double>(raw);
      return o.type == ElemType::Bool ? (raw != 0) : static_cast<double>(static_cast<int64_t>(raw));
    }
    case OpKind::Fact: return in.world->hasFact(o.address) ? 1 : 0;
    default: {
      const uint8_t* p = in.plcMemory + o.address;
      if (o.bit >= 0) return (*p >> o.bit) & 1;
      return isRealType(o.type) ? loadReal(p, o.type) : static_cast<double>(loadInteger(p, o.type));
    }
  }
}

double Expression::evaluate(const ValueSources& in) const {
  std::array<double, kMaxDepth + 1> stack{};
  size_t top = 0;
  for (const Op& op : code_) {
    switch (op.kind) {
      case OpKind::Const: stack[top++] = op.value; break;
      case OpKind::Var:
      case OpKind::Tag:
      case OpKind::Fact: stack[top++] = load(operands_[op.operand], op.kind, in); break;
      case OpKind::Not: stack[top - 1] = stack[top - 1] == 0; break;
      default: {
        const double b = stack[--top], a = stack[top - 1];
        double r = 0;
        switch (op.kind) {
          case OpKind::And: r = a != 0 && b != 0; break;
          case OpKind::Or: r = a != 0 || b != 0; break;
          case OpKind::Xor: r = (a != 0) != (b != 0); break;
          case OpKind::Eq: r = a == b; break;
          case OpKind::Ne: r = a != b; break;
          case OpKind::Lt: r = a < b; break;
          case OpKind::Le: r = a <= b; break;
          case OpKind::Gt: r = a > b; break;
          case OpKind::Ge: r = a >= b; break;
          default: break;
        }
        stack[top - 1] = r;
      }
    }
  }
  return top ? stack[top - 1] : 0;
}

std::string Expression::describeOperands(const ValueSources& in) const {
  std::ostringstream out;
  for (const Op& op : code_) {
    if (op.kind != OpKind::Var && op.kind != OpKind::Tag && op.kind != OpKind::Fact) continue;
    const Operand& o = operands_[op.operand];
    const double v = load(o, op.kind, in);
    if (out.tellp() > 0) out << ", ";
    out << o.name << " = ";
    if (op.kind == OpKind::Fact || o.type == ElemType::Bool) out << (v != 0 ? "TRUE" : "FALSE");
    else out << v;
  }
  return out.str();
}

}  // namespace virtcom::scenario
