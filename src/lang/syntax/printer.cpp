#include "lang/syntax/printer.hpp"

#include "core/iec_value.hpp"

namespace virtcom::st {

namespace {

// Binding strength, loosest first, as the parser reads it: a unary operator applies to the
// primary after it (`-x ** 2` is `(-x) ** 2`); primaries (names, calls, literals) bind tightest.
enum Precedence : int { kOr = 1, kXor, kAnd, kEquality, kComparison, kAdditive, kMultiplicative, kPower, kUnary, kPrimary };

int precedenceOf(BinaryOp op) {
  switch (op) {
    case BinaryOp::Or: case BinaryOp::OrElse: return kOr;
    case BinaryOp::Xor: return kXor;
    case BinaryOp::And: case BinaryOp::AndThen: return kAnd;
    case BinaryOp::Eq: case BinaryOp::Ne: return kEquality;
    case BinaryOp::Lt: case BinaryOp::Le: case BinaryOp::Gt: case BinaryOp::Ge: return kComparison;
    case BinaryOp::Add: case BinaryOp::Sub: return kAdditive;
    case BinaryOp::Mul: case BinaryOp::Div: case BinaryOp::Mod: return kMultiplicative;
    case BinaryOp::Power: return kPower;
  }
  return kPrimary;
}

const char* spelling(BinaryOp op) {
  switch (op) {
    case BinaryOp::Power: return "**";
    case BinaryOp::Mul: return "*";
    case BinaryOp::Div: return "/";
    case BinaryOp::Mod: return "MOD";
    case BinaryOp::Add: return "+";
    case BinaryOp::Sub: return "-";
    case BinaryOp::Lt: return "<";
    case BinaryOp::Le: return "<=";
    case BinaryOp::Gt: return ">";
    case BinaryOp::Ge: return ">=";
    case BinaryOp::Eq: return "=";
    case BinaryOp::Ne: return "<>";
    case BinaryOp::And: return "AND";
    case BinaryOp::Xor: return "XOR";
    case BinaryOp::Or: return "OR";
    case BinaryOp::AndThen: return "AND_THEN";
    case BinaryOp::OrElse: return "OR_ELSE";
  }
  return "?";
}

int precedenceOf(const Expr& e) {
  if (e.kind == ExprKind::Binary) return precedenceOf(e.binaryOp);
  if (e.kind == ExprKind::Unary) return kUnary;
  return kPrimary;
}

std::string wideQuoted(std::string_view raw) {
  std::string out = "\"";
  for (char c : raw) {
    if (c == '"' || c == '$') out += '$';
    if (c == '\n') out += "$N";
    else if (c == '\r') out += "$R";
    else if (c == '\t') out += "$T";
    else out += c;
  }
  return out + "\"";
}

std::string timeLiteral(const Expr& e) {
  auto ns = static_cast<int64_t>(e.intValue);
  std::string text = formatLtimeNs(ns);  // LTIME#1s5ns
  if (e.typePrefix == "LTIME") return text;
  return "T#" + text.substr(text.find('#') + 1);
}

std::string literal(const Expr& e) {
  std::string prefix = e.typePrefix.empty() ? "" : e.typePrefix + "#";
  switch (e.kind) {
    case ExprKind::IntLit: return prefix + std::to_string(e.intValue);
    case ExprKind::RealLit: return prefix + formatLreal(e.realValue);
    case ExprKind::BoolLit: return e.intValue ? "TRUE" : "FALSE";
    case ExprKind::StringLit: return e.wide ? wideQuoted(e.text) : quoteString(e.text);
    case ExprKind::TimeLit: return timeLiteral(e);
    case ExprKind::DateLit: {
      auto v = static_cast<int64_t>(e.intValue);
      if (e.typePrefix == "TOD") return formatTimeOfDay(v);
      if (e.typePrefix == "DT") return formatDateAndTime(v);
      if (e.typePrefix == "LDATE") return formatLdate(v);
      if (e.typePrefix == "LTOD") return formatLtod(v);
      if (e.typePrefix == "LDT") return formatLdt(v);
      return formatDate(v);
    }
    case ExprKind::EnumLit: return e.typePrefix + "#" + e.text;
    default: return {};
  }
}

std::string operand(const Expr& e, int minPrecedence) {
  std::string text = printExpr(e);
  return precedenceOf(e) < minPrecedence ? "(" + text + ")" : text;
}

std::string callArgs(const std::vector<CallArg>& args) {
  std::string out;
  for (const auto& a : args) {
    if (!out.empty()) out += ", ";
    if (a.negated) out += "NOT ";
    if (!a.name.empty()) out += a.name + (a.output ? " => " : " := ");
    if (a.value) out += printExpr(*a.value);
  }
  return out;
}

void line(std::string& out, int indent, const std::string& text) {
  out.append(static_cast<size_t>(indent), '\t');
  out += text;
  out += '\n';
}

void printStatement(const Stmt& s, int indent, std::string& out);

void printBody(std::span<const StmtPtr> body, int indent, std::string& out) {
  for (const auto& s : body)
    if (s) printStatement(*s, indent, out);
}

std::string caseLabels(const CaseBranch& branch) {
  std::string text;
  for (const auto& l : branch.labels) {
    if (!text.empty()) text += ", ";
    text += printExpr(*l.lo);
    if (l.hi) text += ".." + printExpr(*l.hi);
  }
  return text;
}

void printStatement(const Stmt& s, int indent, std::string& out) {
  auto e = [](const ExprPtr& p) { return p ? printExpr(*p) : std::string(); };
  switch (s.kind) {
    case StmtKind::Assign: line(out, indent, e(s.lhs) + " := " + e(s.rhs) + ";"); break;
    case StmtKind::RefAssign: line(out, indent, e(s.lhs) + " REF= " + e(s.rhs) + ";"); break;
    case StmtKind::AttemptAssign: line(out, indent, e(s.lhs) + " ?= " + e(s.rhs) + ";"); break;
    case StmtKind::SetAssign: line(out, indent, e(s.lhs) + " S= " + e(s.rhs) + ";"); break;
    case StmtKind::ResetAssign: line(out, indent, e(s.lhs) + " R= " + e(s.rhs) + ";"); break;
    case StmtKind::Call: line(out, indent, e(s.expr) + ";"); break;
    case StmtKind::If:
      for (size_t i = 0; i < s.branches.size(); ++i) {
        line(out, indent, std::string(i == 0 ? "IF " : "ELSIF ") + e(s.branches[i].cond) + " THEN");
        printBody(s.branches[i].body, indent + 1, out);
      }
      if (s.hasElse || !s.elseBody.empty()) {
        line(out, indent, "ELSE");
        printBody(s.elseBody, indent + 1, out);
      }
      line(out, indent, "END_IF;");
      break;
    case StmtKind::Case:
      line(out, indent, "CASE " + e(s.expr) + " OF");
      for (const auto& branch : s.cases) {
        line(out, indent + 1, caseLabels(branch) + ":");
        printBody(branch.body, indent + 2, out);
      }
      if (s.hasElse || !s.elseBody.empty()) {
        line(out, indent, "ELSE");
        printBody(s.elseBody, indent + 1, out);
      }
      line(out, indent, "END_CASE;");
      break;
    case StmtKind::For:
      line(out, indent, "FOR " + e(s.lhs) + " := " + e(s.rhs) + " TO " + e(s.to) + (s.by ? " BY " + e(s.by) : "") + " DO");
      printBody(s.body, indent + 1, out);
      line(out, indent, "END_FOR;");
      break;
    case StmtKind::While:
      line(out, indent, "WHILE " + e(s.expr) + " DO");
      printBody(s.body, indent + 1, out);
      line(out, indent, "END_WHILE;");
      break;
    case StmtKind::Repeat:
      line(out, indent, "REPEAT");
      printBody(s.body, indent + 1, out);
      line(out, indent, "UNTIL " + e(s.expr));
      line(out, indent, "END_REPEAT;");
      break;
    case StmtKind::Exit: line(out, indent, "EXIT;"); break;
    case StmtKind::Continue: line(out, indent, "CONTINUE;"); break;
    case StmtKind::Return: line(out, indent, "RETURN;"); break;
    case StmtKind::Empty: line(out, indent, ";"); break;
    case StmtKind::Jump: line(out, indent, "JMP " + s.label + ";"); break;
    case StmtKind::Label: line(out, indent, s.label + ":"); break;
  }
}

}  // namespace

std::string printExpr(const Expr& e) {
  auto sub = [](const ExprPtr& p, int minPrecedence) { return p ? operand(*p, minPrecedence) : std::string(); };
  switch (e.kind) {
    case ExprKind::IntLit: case ExprKind::RealLit: case ExprKind::BoolLit: case ExprKind::StringLit:
    case ExprKind::TimeLit: case ExprKind::DateLit: case ExprKind::EnumLit:
      return literal(e);
    case ExprKind::Name: case ExprKind::DirectAddr: return e.text;
    case ExprKind::This: return "THIS";
    case ExprKind::Super: return "SUPER";
    case ExprKind::Member: return sub(e.lhs, kPrimary) + "." + e.text;
    case ExprKind::BitAccess: return sub(e.lhs, kPrimary) + "." + std::to_string(e.intValue);
    case ExprKind::Deref: return sub(e.lhs, kPrimary) + "^";
    case ExprKind::Index: {
      std::string text = sub(e.lhs, kPrimary) + "[";
      for (size_t i = 0; i < e.items.size(); ++i) text += (i ? ", " : "") + (e.items[i] ? printExpr(*e.items[i]) : "");
      return text + "]";
    }
    case ExprKind::Unary: {
      // `- -x` must not print as `--x`; NOT needs a space before a name.
      std::string inner = sub(e.lhs, kUnary);
      if (e.unaryOp == UnaryOp::Not) return "NOT " + inner;
      std::string sign = e.unaryOp == UnaryOp::Neg ? "-" : "+";
      return sign + (!inner.empty() && (inner[0] == '-' || inner[0] == '+') ? " " : "") + inner;
    }
    case ExprKind::Binary: {
      int p = precedenceOf(e.binaryOp);
      return sub(e.lhs, p) + " " + spelling(e.binaryOp) + " " + sub(e.rhs, p + 1);
    }
    case ExprKind::Call: return sub(e.lhs, kPrimary) + "(" + callArgs(e.args) + ")";
    case ExprKind::ArrayInit: {
      std::string text = "[";
      for (size_t i = 0; i < e.items.size(); ++i) text += (i ? ", " : "") + (e.items[i] ? printExpr(*e.items[i]) : "");
      return text + "]";
    }
    case ExprKind::Repeat: return std::to_string(e.intValue) + "(" + (e.lhs ? printExpr(*e.lhs) : "") + ")";
    case ExprKind::StructInit: return "(" + callArgs(e.args) + ")";
  }
  return {};
}

std::string printStatements(std::span<const StmtPtr> stmts, int indent) {
  std::string out;
  printBody(stmts, indent, out);
  return out;
}

}  // namespace virtcom::st
