#include "lang/st/parse/parser.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "core/iec_value.hpp"

namespace virtcom::st {
namespace {

// ---- A compact S-expression rendering of the tree -----------------------------------------

std::string show(const Expr* e);
std::string show(const StmtList& list);

std::string binaryName(BinaryOp op) {
  static constexpr std::string_view kNames[] = {"**", "*", "/", "MOD", "+", "-", "<", "<=", ">", ">=",
                                                "=",  "<>", "AND", "XOR", "OR", "AND_THEN", "OR_ELSE"};
  return std::string(kNames[static_cast<size_t>(op)]);
}

std::string showArgs(const std::vector<CallArg>& args) {
  std::string out;
  for (const CallArg& a : args) {
    out += ' ';
    if (a.name.empty()) {
      out += show(a.value.get());
      continue;
    }
    out += "(" + std::string(a.negated ? "NOT " : "") + a.name + (a.output ? " =>" : " :=");
    if (a.value) out += " " + show(a.value.get());
    out += ")";
  }
  return out;
}

std::string withPrefix(const Expr& e, std::string value) {
  return e.typePrefix.empty() ? value : e.typePrefix + "#" + value;
}

std::string show(const Expr* e) {
  if (e == nullptr) return "null";
  switch (e->kind) {
    case ExprKind::IntLit: return withPrefix(*e, std::to_string(e->intValue));
    case ExprKind::RealLit: return withPrefix(*e, "r" + (std::ostringstream() << e->realValue).str());
    case ExprKind::BoolLit: return withPrefix(*e, e->intValue ? "TRUE" : "FALSE");
    case ExprKind::StringLit: return withPrefix(*e, e->wide ? "\"" + e->text + "\"" : "'" + e->text + "'");
    case ExprKind::TimeLit: return e->typePrefix + "#" + std::to_string(e->intValue) + "ns";
    case ExprKind::DateLit: return e->typePrefix + "#" + std::to_string(e->intValue);
    case ExprKind::EnumLit: return e->typePrefix + "#" + e->text;
    case ExprKind::Name: return e->text.empty() ? "<error>" : e->text;
    case ExprKind::This: return "THIS";
    case ExprKind::Super: return "SUPER";
    case ExprKind::Member: return "(. " + show(e->lhs.get()) + " " + e->text + ")";
    case ExprKind::BitAccess: return "(.bit " + show(e->lhs.get()) + " " + std::to_string(e->intValue) + ")";
    case ExprKind::Deref: return "(^ " + show(e->lhs.get()) + ")";
    case ExprKind::Unary: {
      static constexpr std::string_view kOps[] = {"-", "+", "NOT"};
      return "(" + std::string(kOps[static_cast<size_t>(e->unaryOp)]) + " " + show(e->lhs.get()) + ")";
    }
    case ExprKind::Binary:
      return "(" + binaryName(e->binaryOp) + " " + show(e->lhs.get()) + " " + show(e->rhs.get()) + ")";
    case ExprKind::Call: return "(call " + show(e->lhs.get()) + showArgs(e->args) + ")";
    case ExprKind::Index: {
      std::string out = "([] " + show(e->lhs.get());
      for (const ExprPtr& i : e->items) out += " " + show(i.get());
      return out + ")";
    }
    case ExprKind::ArrayInit: {
      std::string out = "[";
      for (const ExprPtr& i : e->items) out += (out.size() > 1 ? " " : "") + show(i.get());
      return out + "]";
    }
    case ExprKind::Repeat: return "(" + std::to_string(e->intValue) + "x " + show(e->lhs.get()) + ")";
    case ExprKind::StructInit: return "{" + showArgs(e->args).substr(1) + "}";
    case ExprKind::DirectAddr: return e->text;
  }
  return "?";
}

std::string show(const Stmt& s) {
  auto bin = [&](std::string_view op) { return "(" + std::string(op) + " " + show(s.lhs.get()) + " " + show(s.rhs.get()) + ")"; };
  switch (s.kind) {
    case StmtKind::Assign: return bin(":=");
    case StmtKind::RefAssign: return bin("REF=");
    case StmtKind::AttemptAssign: return bin("?=");
    case StmtKind::SetAssign: return bin("S=");
    case StmtKind::ResetAssign: return bin("R=");
    case StmtKind::Call: return show(s.expr.get());
    case StmtKind::If: {
      std::string out = "(if";
      for (const CondBlock& b : s.branches) out += " (" + show(b.cond.get()) + " " + show(b.body) + ")";
      if (s.hasElse) out += " (else " + show(s.elseBody) + ")";
      return out + ")";
    }
    case StmtKind::Case: {
      std::string out = "(case " + show(s.expr.get());
      for (const CaseBranch& b : s.cases) {
        out += " ((";
        for (size_t i = 0; i < b.labels.size(); ++i) {
          out += (i ? " " : "") + show(b.labels[i].lo.get());
          if (b.labels[i].hi) out += ".." + show(b.labels[i].hi.get());
        }
        out += ") " + show(b.body) + ")";
      }
      if (s.hasElse) out += " (else " + show(s.elseBody) + ")";
      return out + ")";
    }
    case StmtKind::For:
      return "(for " + show(s.lhs.get()) + " " + show(s.rhs.get()) + " " + show(s.to.get()) + " " +
             show(s.by.get()) + " " + show(s.body) + ")";
    case StmtKind::While: return "(while " + show(s.expr.get()) + " " + show(s.body) + ")";
    case StmtKind::Repeat: return "(repeat " + show(s.body) + " " + show(s.expr.get()) + ")";
    case StmtKind::Exit: return "EXIT";
    case StmtKind::Continue: return "CONTINUE";
    case StmtKind::Return: return "RETURN";
    case StmtKind::Empty: return "EMPTY";
    case StmtKind::Jump: return "(jmp " + s.label + ")";
    case StmtKind::Label: return "(label " + s.label + ")";
  }
  return "?";
}

std::string show(const StmtList& list) {
  std::string out = "{";
  for (const StmtPtr& s : list) out += (out.size() > 1 ? " " : "") + show(*s);
  return out + "}";
}

std::string show(const TypeSpec& t) {
  switch (t.kind) {
    case TypeSpecKind::Named: return t.name;
    case TypeSpecKind::String:
      return std::string(t.wide ? "WSTRING" : "STRING") + (t.length ? "(" + show(t.length.get()) + ")" : "");
    case TypeSpecKind::Array: {
      std::string out = "ARRAY[";
      for (size_t i = 0; i < t.dims.size(); ++i)
        out += (i ? "," : "") + (t.dims[i].lo ? show(t.dims[i].lo.get()) + ".." + show(t.dims[i].hi.get()) : "*");
      return out + "] OF " + show(*t.element);
    }
    case TypeSpecKind::Pointer: return "POINTER TO " + show(*t.element);
    case TypeSpecKind::Reference: return "REF " + show(*t.element);
    case TypeSpecKind::Subrange: return show(*t.element) + "(" + show(t.lo.get()) + ".." + show(t.hi.get()) + ")";
    case TypeSpecKind::Enum: {
      std::string out = "(";
      for (size_t i = 0; i < t.enumValues.size(); ++i) {
        out += (i ? ", " : "") + t.enumValues[i].name;
        if (t.enumValues[i].value) out += " := " + show(t.enumValues[i].value.get());
      }
      return out + ")" + (t.name.empty() ? "" : " " + t.name);
    }
    case TypeSpecKind::Struct: {
      std::string out = "STRUCT" + (t.name.empty() ? "" : " EXTENDS " + t.name) + " {";
      for (size_t i = 0; i < t.fields.size(); ++i) {
        out += (i ? " " : "") + t.fields[i].names[0].name + ":" + show(t.fields[i].type);
        if (t.fields[i].init) out += ":=" + show(t.fields[i].init.get());
      }
      return out + "}";
    }
  }
  return "?";
}

std::string show(const VarDecl& d) {
  std::string out;
  for (const Attribute& a : d.attributes) out += "{" + a.name + (a.value.empty() ? "" : "=" + a.value) + "} ";
  for (size_t i = 0; i < d.names.size(); ++i) out += (i ? "," : "") + d.names[i].name;
  if (!d.location.empty()) out += " AT " + d.location;
  out += " : " + show(d.type);
  if (!d.fbInitArgs.empty()) out += "(" + showArgs(d.fbInitArgs).substr(1) + ")";
  if (d.edge != EdgeKind::None) out += d.edge == EdgeKind::Rising ? " R_EDGE" : " F_EDGE";
  if (d.init) out += " := " + show(d.init.get());
  return out;
}

// ---- Helpers --------------------------------------------------------------------------------

struct Parsed {
  Diagnostics diags;
  CompilationUnit unit;
  NodeId nextId = 0;
};

std::unique_ptr<Parsed> parse(std::string_view text) {
  auto p = std::make_unique<Parsed>();
  p->unit = parseFile(0, text, p->diags, p->nextId);
  return p;
}

std::string diagText(const Diagnostics& diags) {
  std::string out;
  for (const Diagnostic& d : diags.all())
    out += std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + " " + std::string(d.code) + " " + d.message + "\n";
  return out;
}

// The statements of a program body, or the diagnostics if there were any.
std::string body(std::string_view statements) {
  std::string text = "PROGRAM P\n" + std::string(statements) + "\nEND_PROGRAM\n";
  auto p = parse(text);
  if (!p->diags.all().empty()) return "DIAGS: " + diagText(p->diags);
  if (p->unit.pous.size() != 1) return "no POU";
  return show(p->unit.pous[0]->body);
}

std::string expr(std::string_view e) {
  std::string s = body("x := " + std::string(e) + ";");
  if (s.rfind("DIAGS", 0) == 0) return s;
  return s.substr(7, s.size() - 9);  // strip "{(:= x " and ")}"
}

// The declarations of one VAR block.
std::string vars(std::string_view decls) {
  std::string text = "PROGRAM P\nVAR\n" + std::string(decls) + "\nEND_VAR\nEND_PROGRAM\n";
  auto p = parse(text);
  if (!p->diags.all().empty()) return "DIAGS: " + diagText(p->diags);
  std::string out;
  for (const VarDecl& d : p->unit.pous.at(0)->varBlocks.at(0).vars) out += (out.empty() ? "" : "; ") + show(d);
  return out;
}

std::string diags(std::string_view text) { return diagText(parse(text)->diags); }

// ---- Expressions ----------------------------------------------------------------------------

TEST(ParserExpr, Precedence) {
  EXPECT_EQ(expr("a OR b AND c"), "(OR a (AND b c))");
  EXPECT_EQ(expr("a XOR b OR c"), "(OR (XOR a b) c)");
  EXPECT_EQ(expr("a AND b XOR c"), "(XOR (AND a b) c)");
  EXPECT_EQ(expr("a = b AND c <> d"), "(AND (= a b) (<> c d))");
  EXPECT_EQ(expr("a < b = c >= d"), "(= (< a b) (>= c d))");
  EXPECT_EQ(expr("a + b * c"), "(+ a (* b c))");
  EXPECT_EQ(expr("a - b - c"), "(- (- a b) c)");
  EXPECT_EQ(expr("a * b MOD c / d"), "(/ (MOD (* a b) c) d)");
  EXPECT_EQ(expr("a * b ** c"), "(* a (** b c))");
  EXPECT_EQ(expr("a ** b ** c"), "(** (** a b) c)");
  EXPECT_EQ(expr("-2 ** 2"), "(** (- 2) 2)");
  EXPECT_EQ(expr("NOT a = b"), "(= (NOT a) b)");
  EXPECT_EQ(expr("NOT (a = b)"), "(NOT (= a b))");
  EXPECT_EQ(expr("a & b"), "(AND a b)");
  EXPECT_EQ(expr("a AND_THEN b OR_ELSE c"), "(OR_ELSE (AND_THEN a b) c)");
  EXPECT_EQ(expr("(a + b) * -c"), "(* (+ a b) (- c))");
  EXPECT_EQ(expr("- - +a"), "(- (- (+ a)))");
}

TEST(ParserExpr, Postfix) {
  EXPECT_EQ(expr("a.b[1, 2].c^.d(1)"), "(call (. (^ (. ([] (. a b) 1 2) c)) d) 1)");
  EXPECT_EQ(expr("w.3"), "(.bit w 3)");
  EXPECT_EQ(expr("w.%X3"), "(.bit w 3)");
  EXPECT_EQ(expr("s.arr[i].0"), "(.bit ([] (. s arr) i) 0)");
  EXPECT_EQ(expr("THIS^.x"), "(. (^ THIS) x)");
  EXPECT_EQ(expr("SUPER^.M()"), "(call (. (^ SUPER) M))");
  EXPECT_EQ(expr("p^^"), "(^ (^ p))");
  EXPECT_EQ(expr("fb.Q"), "(. fb Q)");
  EXPECT_EQ(expr("a.END_IF"), "(. a END_IF)");  // any word is a member name after '.'
}

TEST(ParserExpr, CallArguments) {
  EXPECT_EQ(body("fb(IN := x, PT := T#1s, Q => q, ET =>, NOT Q2 => nq);"),
            "{(call fb (IN := x) (PT := TIME#1000000000ns) (Q => q) (ET =>) (NOT Q2 => nq))}");
  EXPECT_EQ(body("f(x, y + 1);"), "{(call f x (+ y 1))}");
  EXPECT_EQ(body("f();"), "{(call f)}");
  EXPECT_EQ(body("obj.Method(1);"), "{(call (. obj Method) 1)}");
  EXPECT_EQ(body("SUPER^();"), "{(call (^ SUPER))}");
}

TEST(ParserExpr, Literals) {
  EXPECT_EQ(expr("1_000"), "1000");
  EXPECT_EQ(expr("16#FF"), "255");
  EXPECT_EQ(expr("1.5"), "r1.5");
  EXPECT_EQ(expr("1e6"), "r1e+06");
  EXPECT_EQ(expr("TRUE"), "TRUE");
  EXPECT_EQ(expr("false"), "FALSE");
  EXPECT_EQ(expr("'it$'s'"), "'it's'");
  EXPECT_EQ(expr("\"wide\""), "\"wide\"");
  EXPECT_EQ(expr("T#1.5s"), "TIME#1500000000ns");
  EXPECT_EQ(expr("T#-5s"), "(- TIME#5000000000ns)");
  EXPECT_EQ(expr("LT#1ms"), "LTIME#1000000ns");
  EXPECT_EQ(expr("TOD#00:00:02"), "TOD#2000");
  EXPECT_EQ(expr("D#1970-01-02"), "DATE#86400");
  EXPECT_EQ(expr("DT#1970-01-01-00:01:00"), "DT#60");
  EXPECT_EQ(expr("%IX0.1"), "%IX0.1");
}

TEST(ParserExpr, TypedLiterals) {
  EXPECT_EQ(expr("INT#5"), "INT#5");
  EXPECT_EQ(expr("int#5"), "INT#5");
  EXPECT_EQ(expr("INT#-5"), "(- INT#5)");
  EXPECT_EQ(expr("DINT#16#FF"), "DINT#255");
  EXPECT_EQ(expr("REAL#1.5"), "REAL#r1.5");
  EXPECT_EQ(expr("REAL#2"), "REAL#r2");
  EXPECT_EQ(expr("BOOL#1"), "BOOL#TRUE");
  EXPECT_EQ(expr("BOOL#FALSE"), "BOOL#FALSE");
  EXPECT_EQ(expr("STRING#'a'"), "STRING#'a'");
  EXPECT_EQ(expr("Color#Red"), "Color#Red");
  EXPECT_EQ(diags("PROGRAM P x := INT#1.5; y := BOOL#2; END_PROGRAM"),
            "1:20 E013 '1.5' is not a valid INT literal\n"
            "1:35 E013 '2' is not a valid BOOL literal\n");
}

TEST(ParserExpr, Initialisers) {
  EXPECT_EQ(expr("[1, 2, 3(0)]"), "[1 2 (3x 0)]");
  EXPECT_EQ(expr("[2()]"), "[(2x null)]");
  EXPECT_EQ(expr("(x := 1, y := 2)"), "{(x := 1) (y := 2)}");
  EXPECT_EQ(expr("[(x := 1), (x := 2)]"), "[{(x := 1)} {(x := 2)}]");
  EXPECT_EQ(expr("(a := (b := 1), c := [1, 2])"), "{(a := {(b := 1)}) (c := [1 2])}");
}

TEST(ParserExpr, ContextKeywordsAreNames) {
  EXPECT_EQ(expr("get + set + on + with + task + resource"), "(+ (+ (+ (+ (+ get set) on) with) task) resource)");
}

// ---- Statements -----------------------------------------------------------------------------

// MOD, AND, OR, XOR and NOT written as standard function calls.
TEST(ParserExpr, OperatorsAsFunctionCalls) {
  EXPECT_EQ(expr("MOD(a, b)"), "(call MOD a b)");
  EXPECT_EQ(expr("AND(a, b, c)"), "(call AND a b c)");
  EXPECT_EQ(expr("or(a, b)"), "(call OR a b)");
  EXPECT_EQ(expr("Xor(a, b) OR c"), "(OR (call XOR a b) c)");
  EXPECT_EQ(expr("a + MOD(b, 2) * 3"), "(+ a (* (call MOD b 2) 3))");
  EXPECT_EQ(expr("-MOD(a, 2)"), "(- (call MOD a 2))");
  EXPECT_EQ(expr("AND(IN1 := a, IN2 := b)"), "(call AND (IN1 := a) (IN2 := b))");
  EXPECT_EQ(body("f(AND(a, b), OR(c, d));"), "{(call f (call AND a b) (call OR c d))}");
  // Between operands they stay binary operators, also before a parenthesis.
  EXPECT_EQ(expr("a MOD (b)"), "(MOD a b)");
  EXPECT_EQ(expr("a AND (b OR c)"), "(AND a (OR b c))");
  EXPECT_EQ(expr("a XOR(b)"), "(XOR a b)");
  // NOT: a parenthesised operand stays the unary operator; named or several arguments make a call.
  EXPECT_EQ(expr("NOT (a OR b)"), "(NOT (OR a b))");
  EXPECT_EQ(expr("NOT(a)"), "(NOT a)");
  EXPECT_EQ(expr("NOT (a) AND b"), "(AND (NOT a) b)");
  EXPECT_EQ(expr("NOT (arr)[1]"), "(NOT ([] arr 1))");
  EXPECT_EQ(expr("NOT NOT(a)"), "(NOT (NOT a))");
  EXPECT_EQ(expr("NOT(a, b)"), "(call NOT a b)");
  EXPECT_EQ(expr("NOT(IN := a)"), "(call NOT (IN := a))");
  EXPECT_EQ(expr("NOT(a, b) OR c"), "(OR (call NOT a b) c)");
  // The call and its callee are located at the keyword.
  auto p = parse("PROGRAM P\nx := 1 + MOD(a, b);\ny := NOT(a, b);\nEND_PROGRAM\n");
  ASSERT_EQ(diagText(p->diags), "");
  const Expr& mod = *p->unit.pous[0]->body[0]->rhs->rhs;
  EXPECT_EQ(mod.kind, ExprKind::Call);
  EXPECT_TRUE(mod.loc.line == 2 && mod.loc.col == 10 && mod.lhs->loc.col == 10);
  const Expr& notCall = *p->unit.pous[0]->body[1]->rhs;
  EXPECT_EQ(notCall.kind, ExprKind::Call);
  EXPECT_TRUE(notCall.loc.line == 3 && notCall.loc.col == 6 && notCall.lhs->loc.col == 6);
  // Errors inside stay single.
  EXPECT_EQ(body("x := MOD(a, , b);"), "DIAGS: 2:13 E006 expected an expression, found ','\n");
  EXPECT_EQ(body("x := NOT(a, b;"), "DIAGS: 2:14 E006 expected ')' to close the argument list, found ';'\n");
}

// CODESYS accepts one trailing comma before ')'; an empty argument elsewhere stays an error.
TEST(ParserExpr, TrailingCommaInCallArguments) {
  EXPECT_EQ(expr("f(a, b,)"), "(call f a b)");
  EXPECT_EQ(expr("fb(IN := x, Q => q,)"), "(call fb (IN := x) (Q => q))");
  EXPECT_EQ(body("x := f(,);"), "DIAGS: 2:8 E006 expected an expression, found ','\n");
  EXPECT_EQ(body("x := f(a,,);"), "DIAGS: 2:10 E006 expected an expression, found ','\n");
}

TEST(ParserStmt, Assignments) {
  EXPECT_EQ(body("a := 1; r REF= x; q S= go; q R= stop; %QX0.0 := TRUE;"),
            "{(:= a 1) (REF= r x) (S= q go) (R= q stop) (:= %QX0.0 TRUE)}");
  EXPECT_EQ(body("THIS^.x := 1;"), "{(:= (. (^ THIS) x) 1)}");
  EXPECT_EQ(body("r ?= itf; pFb ?= THIS^;"), "{(?= r itf) (?= pFb (^ THIS))}");
  EXPECT_EQ(body("IF S = 1 THEN ; END_IF"), "{(if ((= S 1) {EMPTY}))}");
}

TEST(ParserStmt, If) {
  EXPECT_EQ(body("IF a THEN x := 1; ELSIF b THEN x := 2; ELSIF c THEN ; ELSE x := 3; END_IF;"),
            "{(if (a {(:= x 1)}) (b {(:= x 2)}) (c {EMPTY}) (else {(:= x 3)}))}");
  EXPECT_EQ(body("IF a THEN END_IF IF b THEN END_IF"), "{(if (a {})) (if (b {}))}");
}

TEST(ParserStmt, Case) {
  EXPECT_EQ(body("CASE s OF\n"
                 "  1, 2: x := 1;\n"
                 "        y := 2;\n"
                 "  3..5: f(x);\n"
                 "  Color.Red, Color#Blue: ;\n"
                 "  -1: x := 0;\n"
                 "ELSE\n"
                 "  x := 9;\n"
                 "END_CASE"),
            "{(case s ((1 2) {(:= x 1) (:= y 2)}) ((3..5) {(call f x)}) (((. Color Red) Color#Blue) {EMPTY}) "
            "(((- 1)) {(:= x 0)}) (else {(:= x 9)}))}");
  EXPECT_EQ(body("CASE s OF 1: CASE t OF 2: a := 1; END_CASE 3: b := 2; END_CASE"),
            "{(case s ((1) {(case t ((2) {(:= a 1)}))}) ((3) {(:= b 2)}))}");
  EXPECT_EQ(body("CASE s OF 1: IF a THEN b := 1; ELSE b := 2; END_IF ELSE c := 3; END_CASE"),
            "{(case s ((1) {(if (a {(:= b 1)}) (else {(:= b 2)}))}) (else {(:= c 3)}))}");
}

TEST(ParserStmt, Loops) {
  EXPECT_EQ(body("FOR i := 1 TO 10 BY 2 DO a[i] := 0; END_FOR"), "{(for i 1 10 2 {(:= ([] a i) 0)})}");
  EXPECT_EQ(body("FOR i := 0 TO n - 1 DO EXIT; END_FOR;"), "{(for i 0 (- n 1) null {EXIT})}");
  EXPECT_EQ(body("WHILE a < 10 DO a := a + 1; CONTINUE; END_WHILE"), "{(while (< a 10) {(:= a (+ a 1)) CONTINUE})}");
  EXPECT_EQ(body("REPEAT a := a + 1; UNTIL a > 10 END_REPEAT"), "{(repeat {(:= a (+ a 1))} (> a 10))}");
  EXPECT_EQ(body("RETURN; ;"), "{RETURN EMPTY}");
}

TEST(ParserStmt, JumpsAndLabels) {
  EXPECT_EQ(body("again: x := x + 1; IF x < 3 THEN JMP again; END_IF"),
            "{(label again) (:= x (+ x 1)) (if ((< x 3) {(jmp again)}))}");
  // A label needs no statement after it; JMP is no reserved word.
  EXPECT_EQ(body("IF a THEN JMP done; done: END_IF jmp := 1; theEnd:"),
            "{(if (a {(jmp done) (label done)})) (:= jmp 1) (label theEnd)}");
  // In a CASE branch `name:` starts the next branch (an enumeration value is a label there).
  EXPECT_EQ(body("CASE s OF 1: x := 1; Red: x := 2; END_CASE"), "{(case s ((1) {(:= x 1)}) ((Red) {(:= x 2)}))}");
}

// ---- Declarations -----------------------------------------------------------------------------

TEST(ParserDecl, Variables) {
  EXPECT_EQ(vars("a, b, c : INT := 5;"), "a,b,c : INT := 5");
  EXPECT_EQ(vars("x AT %IX0.0 : BOOL;"), "x AT %IX0.0 : BOOL");
  EXPECT_EQ(vars("inst : FB_T(a := 1, b := 2);"), "inst : FB_T((a := 1) (b := 2))");
  EXPECT_EQ(vars("inst : FB_T(1, 2);"), "inst : FB_T(1 2)");
  EXPECT_EQ(vars("s : STRING(20) := 'abc'; t : STRING[20]; u : STRING; w : WSTRING(5);"),
            "s : STRING(20) := 'abc'; t : STRING(20); u : STRING; w : WSTRING(5)");
  EXPECT_EQ(vars("arr : ARRAY[1..3, 0..1] OF INT := [1, 2, 3(0)];"), "arr : ARRAY[1..3,0..1] OF INT := [1 2 (3x 0)]");
  EXPECT_EQ(vars("pts : ARRAY[0..1] OF Point := [(x := 1), (x := 2)];"),
            "pts : ARRAY[0..1] OF Point := [{(x := 1)} {(x := 2)}]");
  EXPECT_EQ(vars("p : Point := (x := 1, y := 2);"), "p : Point := {(x := 1) (y := 2)}");
  EXPECT_EQ(vars("p : POINTER TO INT; r : REFERENCE TO INT; q : REF_TO INT;"),
            "p : POINTER TO INT; r : REF INT; q : POINTER TO INT");  // IEC REF_TO is pointer-like
  EXPECT_EQ(vars("state : (Idle, Run := 5) := Idle;"), "state : (Idle, Run := 5) := Idle");
  EXPECT_EQ(vars("x : INT(0..10) := 5;"), "x : INT(0..10) := 5");
  EXPECT_EQ(vars("go : BOOL R_EDGE; stop : bool f_edge := TRUE; r_edge : BOOL;"),
            "go : BOOL R_EDGE; stop : bool F_EDGE := TRUE; r_edge : BOOL");
  EXPECT_EQ(vars("m : ARRAY[*] OF INT; t : Lib.TON;"), "m : ARRAY[*] OF INT; t : Lib.TON");
  EXPECT_EQ(vars("a : ARRAY[1..2] OF ARRAY[1..2] OF POINTER TO BYTE;"),
            "a : ARRAY[1..2] OF ARRAY[1..2] OF POINTER TO BYTE");
}

TEST(ParserDecl, VarBlockSectionsAndQualifiers) {
  auto p = parse(
      "FUNCTION_BLOCK F\n"
      "VAR_INPUT a : INT; END_VAR VAR_OUTPUT b : INT; END_VAR VAR_IN_OUT c : INT; END_VAR\n"
      "VAR_TEMP d : INT; END_VAR VAR_EXTERNAL e : INT; END_VAR VAR_INST f : INT; END_VAR\n"
      "VAR_STAT g : INT; END_VAR VAR CONSTANT h : INT := 1; END_VAR VAR RETAIN PERSISTENT i : INT; END_VAR\n"
      "VAR NON_RETAIN j : INT; END_VAR VAR_GLOBAL k : INT; END_VAR\n"
      "END_FUNCTION_BLOCK\n");
  ASSERT_EQ(diagText(p->diags), "");
  const auto& blocks = p->unit.pous.at(0)->varBlocks;
  ASSERT_EQ(blocks.size(), 11u);
  std::vector<VarSection> expected = {VarSection::Input, VarSection::Output, VarSection::InOut, VarSection::Temp,
                                      VarSection::External, VarSection::Inst, VarSection::Stat, VarSection::Var,
                                      VarSection::Var, VarSection::Var, VarSection::Global};
  for (size_t i = 0; i < blocks.size(); ++i) EXPECT_EQ(blocks[i].section, expected[i]) << i;
  EXPECT_TRUE(blocks[7].constant);
  EXPECT_TRUE(blocks[8].retain);
  EXPECT_TRUE(blocks[8].persistent);
  EXPECT_FALSE(blocks[9].retain);
}

TEST(ParserDecl, Types) {
  auto p = parse(
      "{attribute 'qualified_only'}\n"
      "TYPE\n"
      "  Color : (Red, Green := 5, Blue) DINT := Green;\n"
      "  {attribute 'pack_mode' := '1'}\n"
      "  Point : STRUCT x : INT := 1; y : INT; END_STRUCT\n"
      "  Point3 : STRUCT EXTENDS Point z : INT; END_STRUCT;\n"
      "  Point4 EXTENDS Point : STRUCT w : INT; END_STRUCT\n"
      "  Level : INT (0..100) := 50;\n"
      "  Alias : INT;\n"
      "  Arr : ARRAY[1..3] OF Point;\n"
      "  Name : STRING(32);\n"
      "END_TYPE\n");
  ASSERT_EQ(diagText(p->diags), "");
  const auto& types = p->unit.types;
  ASSERT_EQ(types.size(), 8u);
  EXPECT_EQ(types[0].name, "Color");
  EXPECT_EQ(show(types[0].spec), "(Red, Green := 5, Blue) DINT");
  EXPECT_EQ(show(types[0].init.get()), "Green");
  EXPECT_EQ(types[0].attributes.at(0).name, "qualified_only");
  EXPECT_EQ(show(types[1].spec), "STRUCT {x:INT:=1 y:INT}");
  EXPECT_EQ(types[1].attributes.at(0).value, "1");
  EXPECT_EQ(show(types[2].spec), "STRUCT EXTENDS Point {z:INT}");
  EXPECT_EQ(show(types[3].spec), "STRUCT EXTENDS Point {w:INT}");
  EXPECT_EQ(show(types[4].spec), "INT(0..100)");
  EXPECT_EQ(show(types[4].init.get()), "50");
  EXPECT_EQ(show(types[5].spec), "INT");
  EXPECT_EQ(show(types[6].spec), "ARRAY[1..3] OF Point");
  EXPECT_EQ(show(types[7].spec), "STRING(32)");
}

TEST(ParserDecl, UnionIsAStructMarkedAsUnion) {
  auto p = parse("TYPE U : UNION a : INT; b : REAL; END_UNION END_TYPE");
  ASSERT_EQ(p->unit.types.size(), 1u);
  EXPECT_EQ(p->unit.types[0].spec.kind, TypeSpecKind::Struct);
  EXPECT_TRUE(p->unit.types[0].spec.isUnion);
  EXPECT_EQ(p->unit.types[0].spec.fields.size(), 2u);
  EXPECT_EQ(diags("TYPE U : UNION a : INT; END_STRUCT END_TYPE"), "1:25 E007 expected 'END_UNION' to close 'UNION' at line 1, found 'END_STRUCT'\n");
}

TEST(ParserDecl, Attributes) {
  auto p = parse(
      "{attribute 'call_after_init'}\n"
      "FUNCTION_BLOCK F\n"
      "VAR\n"
      "  {attribute 'hide'}\n"
      "  {attribute 'monitoring' := 'call'}\n"
      "  a : INT;\n"
      "  {warning 'ignored'}\n"
      "  b : INT;\n"
      "END_VAR\n"
      "{attribute 'm'} METHOD M END_METHOD\n"
      "END_FUNCTION_BLOCK\n");
  ASSERT_EQ(diagText(p->diags), "");
  const Pou& fb = *p->unit.pous.at(0);
  EXPECT_EQ(fb.attributes.at(0).name, "call_after_init");
  EXPECT_EQ(show(fb.varBlocks[0].vars[0]), "{hide} {monitoring=call} a : INT");
  EXPECT_EQ(show(fb.varBlocks[0].vars[1]), "b : INT");
  EXPECT_EQ(fb.methods.at(0)->attributes.at(0).name, "m");
}

TEST(ParserDecl, GlobalVariableListCollectsAllBlocks) {
  auto p = parse(
      "{attribute 'qualified_only'}\n"
      "VAR_GLOBAL\n  g1 : INT;\nEND_VAR\n"
      "VAR_GLOBAL CONSTANT\n  kMax : INT := 10;\nEND_VAR\n"
      "VAR_GLOBAL RETAIN\n  r : INT;\nEND_VAR\n");
  ASSERT_EQ(diagText(p->diags), "");
  ASSERT_EQ(p->unit.globals.size(), 1u);
  const GlobalVarList& gvl = p->unit.globals[0];
  EXPECT_EQ(gvl.name, "");
  ASSERT_EQ(gvl.blocks.size(), 3u);
  EXPECT_TRUE(gvl.blocks[1].constant);
  EXPECT_TRUE(gvl.blocks[2].retain);
  ASSERT_EQ(gvl.attributes.size(), 1u);
  EXPECT_EQ(gvl.loc.line, 2u);
}

// ---- POUs -------------------------------------------------------------------------------------

TEST(ParserPou, ProgramAndFunction) {
  auto p = parse(
      "FUNCTION Add3 : INT\nVAR_INPUT a, b, c : INT; END_VAR\nAdd3 := a + b + c;\nEND_FUNCTION\n"
      "PROGRAM Main\nVAR x : INT; END_VAR\nx := Add3(1, 2, 3);\nEND_PROGRAM\n");
  ASSERT_EQ(diagText(p->diags), "");
  ASSERT_EQ(p->unit.pous.size(), 2u);
  const Pou& f = *p->unit.pous[0];
  EXPECT_TRUE(f.kind == PouKind::Function && f.name == "Add3");
  EXPECT_TRUE(f.hasReturnType);
  EXPECT_EQ(show(f.returnType), "INT");
  EXPECT_TRUE(f.hasBody);
  EXPECT_TRUE(f.loc.line == 1 && f.loc.col == 10 && f.endLoc.line == 4);
  EXPECT_EQ(show(f.body), "{(:= Add3 (+ (+ a b) c))}");
  EXPECT_EQ(p->unit.pous[1]->kind, PouKind::Program);
}

TEST(ParserPou, FunctionBlockWithMembers) {
  auto p = parse(
      "FUNCTION_BLOCK ABSTRACT PUBLIC FB_Motor EXTENDS FB_Base IMPLEMENTS I_Motor, Lib.I_Dev\n"
      "VAR_INPUT run : BOOL; END_VAR\n"
      "run := run;\n"
      "METHOD PUBLIC Start : BOOL\n"
      "VAR_INPUT speed : INT; END_VAR\n"
      "Start := TRUE;\n"
      "END_METHOD\n"
      "METHOD PROTECTED ABSTRACT Stop\n"
      "END_METHOD\n"
      "METHOD FINAL Internal : INT\n"
      "END_METHOD\n"
      "PROPERTY Speed : INT\n"
      "GET\n  VAR v : INT; END_VAR\n  Speed := v;\nEND_GET\n"
      "SET\n  v := Speed;\nEND_SET\n"
      "END_PROPERTY\n"
      "ACTION Reset:\n  run := FALSE;\nEND_ACTION\n"
      "END_FUNCTION_BLOCK\n");
  ASSERT_EQ(diagText(p->diags), "");
  const Pou& fb = *p->unit.pous.at(0);
  EXPECT_TRUE(fb.kind == PouKind::FunctionBlock && fb.isAbstract && fb.access == Access::Public);
  EXPECT_EQ(fb.name, "FB_Motor");
  EXPECT_EQ(fb.extends, "FB_Base");
  EXPECT_EQ(fb.implements, (std::vector<std::string>{"I_Motor", "Lib.I_Dev"}));
  ASSERT_EQ(fb.methods.size(), 3u);
  const Pou& start = *fb.methods[0];
  EXPECT_TRUE(start.kind == PouKind::Method && start.access == Access::Public);
  EXPECT_TRUE(start.hasBody);
  EXPECT_EQ(show(start.returnType), "BOOL");
  EXPECT_EQ(start.varBlocks.size(), 1u);
  EXPECT_EQ(show(start.body), "{(:= Start TRUE)}");
  EXPECT_TRUE(fb.methods[1]->isAbstract && !fb.methods[1]->hasBody && fb.methods[1]->access == Access::Protected);
  EXPECT_TRUE(fb.methods[2]->name == "Internal" && fb.methods[2]->isFinal);
  ASSERT_EQ(fb.properties.size(), 1u);
  const Property& prop = fb.properties[0];
  EXPECT_EQ(prop.name, "Speed");
  EXPECT_EQ(show(prop.type), "INT");
  ASSERT_TRUE(prop.getter && prop.setter);
  EXPECT_TRUE(prop.getter->kind == PouKind::PropertyGet && prop.getter->name == "Speed");
  EXPECT_EQ(prop.getter->varBlocks.size(), 1u);
  EXPECT_EQ(show(prop.getter->body), "{(:= Speed v)}");
  EXPECT_EQ(prop.setter->kind, PouKind::PropertySet);
  EXPECT_EQ(show(prop.setter->body), "{(:= v Speed)}");
  ASSERT_EQ(fb.actions.size(), 1u);
  EXPECT_TRUE(fb.actions[0]->kind == PouKind::Action && fb.actions[0]->name == "Reset");
  EXPECT_EQ(show(fb.actions[0]->body), "{(:= run FALSE)}");
}

TEST(ParserPou, Interface) {
  auto p = parse(
      "INTERFACE I_Motor EXTENDS I_A, I_B\n"
      "METHOD Start : BOOL\nVAR_INPUT speed : INT; END_VAR\nEND_METHOD\n"
      "PROPERTY Speed : INT\nGET END_GET\nSET END_SET\nEND_PROPERTY\n"
      "END_INTERFACE\n");
  ASSERT_EQ(diagText(p->diags), "");
  ASSERT_EQ(p->unit.interfaces.size(), 1u);
  const Interface& itf = p->unit.interfaces[0];
  EXPECT_EQ(itf.name, "I_Motor");
  EXPECT_EQ(itf.extends, (std::vector<std::string>{"I_A", "I_B"}));
  ASSERT_EQ(itf.methods.size(), 1u);
  EXPECT_FALSE(itf.methods[0]->hasBody);
  ASSERT_EQ(itf.properties.size(), 1u);
  ASSERT_TRUE(itf.properties[0].getter && itf.properties[0].setter);
  EXPECT_FALSE(itf.properties[0].getter->hasBody);
  EXPECT_EQ(diags("INTERFACE I METHOD M x := 1; END_METHOD END_INTERFACE"),
            "1:22 E006 a method of an INTERFACE cannot have statements\n");
}

TEST(ParserPou, Configuration) {
  auto p = parse(
      "CONFIGURATION Cfg\n"
      "VAR_GLOBAL g : INT; END_VAR\n"
      "RESOURCE Res ON PLC\n"
      "  TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);\n"
      "  PROGRAM Main WITH Fast : MainPrg (a := 1);\n"
      "  PROGRAM Other : OtherPrg;\n"
      "END_RESOURCE\n"
      "END_CONFIGURATION\n"
      "CONFIGURATION Simple\n"
      "  TASK T1 (INTERVAL := T#5ms);\n"
      "  PROGRAM P1 WITH T1 : Prg;\n"
      "END_CONFIGURATION\n");
  ASSERT_EQ(diagText(p->diags), "");
  ASSERT_EQ(p->unit.configurations.size(), 2u);
  const Configuration& cfg = p->unit.configurations[0];
  EXPECT_EQ(cfg.name, "Cfg");
  EXPECT_EQ(cfg.globals.size(), 1u);
  ASSERT_EQ(cfg.resources.size(), 1u);
  const Resource& res = cfg.resources[0];
  EXPECT_TRUE(res.name == "Res" && res.onName == "PLC");
  EXPECT_EQ(res.tasks.at(0).name, "Fast");
  EXPECT_EQ(showArgs(res.tasks[0].settings), " (INTERVAL := TIME#10000000ns) (PRIORITY := 1)");
  ASSERT_EQ(res.programs.size(), 2u);
  EXPECT_TRUE(res.programs[0].instanceName == "Main" && res.programs[0].taskName == "Fast" &&
              res.programs[0].typeName == "MainPrg");
  EXPECT_EQ(showArgs(res.programs[0].args), " (a := 1)");
  EXPECT_EQ(res.programs[1].taskName, "");
  const Configuration& simple = p->unit.configurations[1];
  ASSERT_EQ(simple.resources.size(), 1u);
  EXPECT_TRUE(simple.resources[0].name.empty() && simple.resources[0].tasks.size() == 1 &&
              simple.resources[0].programs.size() == 1);
}

TEST(ParserPou, NodeIdsAreUniqueAndSharedAcrossFiles) {
  Diagnostics d;
  NodeId next = 0;
  CompilationUnit a = parseFile(0, "PROGRAM A x := 1 + 2; IF x THEN y := 3; END_IF END_PROGRAM", d, next);
  NodeId afterFirst = next;
  CompilationUnit b = parseFile(1, "PROGRAM B x := 1; END_PROGRAM", d, next);
  EXPECT_EQ(d.all().size(), 0u);
  EXPECT_EQ(afterFirst, 10u);  // 3 statements, 7 expressions
  EXPECT_EQ(next, 13u);
  std::set<NodeId> ids;
  std::function<void(const Expr*)> visit = [&](const Expr* e) {
    if (!e) return;
    EXPECT_TRUE(ids.insert(e->id).second);
    visit(e->lhs.get());
    visit(e->rhs.get());
  };
  const Stmt& ifStmt = *a.pous[0]->body[1];
  visit(a.pous[0]->body[0]->lhs.get());
  visit(a.pous[0]->body[0]->rhs.get());
  visit(ifStmt.branches[0].cond.get());
  EXPECT_EQ(b.pous[0]->body[0]->lhs->id, 11u);
  EXPECT_EQ(b.pous[0]->body[0]->id, 12u);
  EXPECT_EQ(b.fileId, 1u);
  EXPECT_EQ(b.pous[0]->body[0]->loc.fileId, 1u);
}

// The fuzz seed corpus doubles as a set of realistic programs: all but errors.st must be clean.
TEST(ParserPou, SeedCorpusParsesCleanly) {
  std::filesystem::path dir = std::filesystem::path(VIRTCOM_SOURCE_DIR) / "tests/fuzz/corpus/st";
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto p = parse(text);
    ++files;
    if (entry.path().filename() == "errors.st") {
      EXPECT_EQ(diagText(p->diags),
                "2:13 E006 expected ';' after variable declaration, found 'END_VAR'\n"
                "4:1 E006 expected ';' after statement, found 'y'\n"
                "4:11 E006 expected an expression, found ';'\n"
                "5:18 E006 expected ';' after statement, found 'END_IF'\n"
                "6:1 E006 unexpected 'END_WHILE': there is no open WHILE\n"
                "7:13 E006 expected ':' after CASE label, found 'x'\n");
    } else {
      EXPECT_EQ(diagText(p->diags), "") << entry.path();
      EXPECT_FALSE(p->unit.pous.empty() && p->unit.types.empty() && p->unit.globals.empty() &&
                   p->unit.configurations.empty())
          << entry.path();
    }
  }
  EXPECT_GE(files, 10u);
}

TEST(ParserPou, LocationsPointAtTheRightTokens) {
  auto p = parse("PROGRAM Main\nVAR\n  a, bb : INT;\nEND_VAR\n  x := a + s.m[1];\n  f(1);\nEND_PROGRAM\n");
  ASSERT_EQ(diagText(p->diags), "");
  const Pou& pou = *p->unit.pous[0];
  EXPECT_EQ(pou.loc.line, 1u);
  EXPECT_EQ(pou.loc.col, 9u);
  EXPECT_EQ(pou.endLoc.line, 7u);
  const VarDecl& decl = pou.varBlocks[0].vars[0];
  EXPECT_EQ(decl.names[1].loc.line, 3u);
  EXPECT_EQ(decl.names[1].loc.col, 6u);
  EXPECT_EQ(decl.type.loc.col, 11u);
  const Stmt& assign = *pou.body[0];
  EXPECT_EQ(assign.loc.line, 5u);
  EXPECT_EQ(assign.loc.col, 3u);
  const Expr& sum = *assign.rhs;
  EXPECT_EQ(sum.loc.col, 10u);           // the operator
  EXPECT_EQ(sum.rhs->loc.col, 15u);      // '[' of the index
  EXPECT_EQ(sum.rhs->lhs->loc.col, 14u); // member name m
  const Stmt& call = *pou.body[1];
  EXPECT_EQ(call.kind, StmtKind::Call);
  EXPECT_EQ(call.loc.line, 6u);
  EXPECT_EQ(call.expr->loc.col, 3u);     // the callee
}

TEST(ParserPou, LocationsCarryTheFileId) {
  Diagnostics d;
  NodeId next = 0;
  CompilationUnit u = parseFile(7, "PROGRAM P x := ; END_PROGRAM", d, next);
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_EQ(d.all()[0].loc.fileId, 7u);
  EXPECT_EQ(u.pous[0]->loc.fileId, 7u);
}

TEST(ParserPou, SmallCases) {
  EXPECT_EQ(body(""), "{}");
  EXPECT_EQ(body("f(NOT a, -b);"), "{(call f (NOT a) (- b))}");
  EXPECT_EQ(body("a[i].b.c := x.y^.z;"), "{(:= (. (. ([] a i) b) c) (. (^ (. x y)) z))}");
  auto p = parse("INTERFACE I PROPERTY P : INT END_PROPERTY END_INTERFACE");
  ASSERT_EQ(diagText(p->diags), "");
  EXPECT_FALSE(p->unit.interfaces[0].properties[0].getter);
  EXPECT_EQ(diags("FUNCTION F END_FUNCTION"), "");
  EXPECT_FALSE(parse("FUNCTION F END_FUNCTION")->unit.pous[0]->hasReturnType);
  EXPECT_EQ(diags("FUNCTION_BLOCK F METHOD ABSTRACT M x := 1; END_METHOD END_FUNCTION_BLOCK"),
            "1:36 E006 an ABSTRACT method cannot have statements\n");
  EXPECT_EQ(diags("PROGRAM P VAR_CONFIG x : INT; END_VAR END_PROGRAM"),
            "1:11 E011 VAR_CONFIG belongs in a CONFIGURATION (inst.var AT %IX1.0 : BOOL;); here its declarations are read as VAR\n");
}

// TwinCAT/CODESYS exports put METHODs, PROPERTYs and ACTIONs before the body, others after it:
// statements before, between and after them all belong to the body, in order.
TEST(ParserPou, BodyAroundMembers) {
  auto p = parse(
      "PROGRAM P\nVAR x, y, z : INT; END_VAR\n"
      "ACTION A:\n  x := 1;\nEND_ACTION\n"
      "x := 2;\n"
      "METHOD M : INT\nM := 1;\nEND_METHOD\n"
      "y := 3;\n"
      "PROPERTY Q : INT\nGET Q := x; END_GET\nEND_PROPERTY\n"
      "ACTION B:\n  y := 1;\nEND_ACTION\n"
      "z := 4;\n"
      "END_PROGRAM\n");
  ASSERT_EQ(diagText(p->diags), "");
  const Pou& prog = *p->unit.pous.at(0);
  EXPECT_EQ(show(prog.body), "{(:= x 2) (:= y 3) (:= z 4)}");
  ASSERT_EQ(prog.actions.size(), 2u);
  EXPECT_EQ(show(prog.actions[0]->body), "{(:= x 1)}");
  EXPECT_EQ(prog.actions[1]->name, "B");
  ASSERT_EQ(prog.methods.size(), 1u);
  EXPECT_EQ(show(prog.methods[0]->body), "{(:= M 1)}");
  ASSERT_EQ(prog.properties.size(), 1u);
  EXPECT_EQ(prog.endLoc.line, 18u);

  // A METHOD before the body of an FB, the TwinCAT layout.
  auto fb = parse(
      "FUNCTION_BLOCK FB\nVAR_OUTPUT count : INT; END_VAR\n"
      "METHOD Peek : INT\nPeek := count + 100;\nEND_METHOD\n"
      "count := count + 1;\nEND_FUNCTION_BLOCK\n");
  ASSERT_EQ(diagText(fb->diags), "");
  EXPECT_EQ(show(fb->unit.pous.at(0)->body), "{(:= count (+ count 1))}");
  EXPECT_EQ(fb->unit.pous[0]->methods.size(), 1u);

  // Members only, and the body only: nothing changes for them.
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nMETHOD M\nEND_METHOD\nACTION A: END_ACTION\nEND_FUNCTION_BLOCK"), "");
  // Declarations still come first.
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nMETHOD M\nEND_METHOD\nVAR x : INT; END_VAR\nEND_FUNCTION_BLOCK"),
            "4:1 E006 variable declarations must come before the first METHOD, PROPERTY or ACTION\n");
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nMETHOD M\nEND_METHOD\nx := 1;\nVAR y : INT; END_VAR\nEND_FUNCTION_BLOCK"),
            "5:1 E006 variable declarations must come before the first statement\n");
  // A FUNCTION has no members: a METHOD in it is reported once, and its END_FUNCTION is still found.
  auto f = parse("FUNCTION F : INT\nF := 1;\nMETHOD M\nEND_METHOD\nF := 2;\nEND_FUNCTION\nPROGRAM P END_PROGRAM");
  EXPECT_EQ(diagText(f->diags), "3:1 E006 a FUNCTION cannot have METHODs, PROPERTYs or ACTIONs\n");
  ASSERT_EQ(f->unit.pous.size(), 2u);
  EXPECT_EQ(show(f->unit.pous[0]->body), "{(:= F 1) (:= F 2)}");
  EXPECT_TRUE(f->unit.pous[0]->methods.empty());
}

// `PROGRAM P : BOOL`: one error at the ':', the rest of the POU parses normally.
TEST(ParserPou, ReturnTypeOnlyForFunctions) {
  auto p = parse("PROGRAM MAIN : BOOL\nVAR\n  x : INT;\nEND_VAR\nx := 1;\nEND_PROGRAM\n");
  EXPECT_EQ(diagText(p->diags), "1:14 E006 a PROGRAM has no return type; only a FUNCTION or METHOD has one\n");
  const Pou& prog = *p->unit.pous.at(0);
  EXPECT_EQ(prog.name, "MAIN");
  EXPECT_FALSE(prog.hasReturnType);
  EXPECT_EQ(prog.varBlocks.size(), 1u);
  EXPECT_EQ(show(prog.body), "{(:= x 1)}");
  auto fb = parse("FUNCTION_BLOCK FB : ARRAY[0..1] OF INT EXTENDS Base\nx := 1;\nEND_FUNCTION_BLOCK\n");
  EXPECT_EQ(diagText(fb->diags),
            "1:19 E006 a FUNCTION_BLOCK has no return type; only a FUNCTION or METHOD has one\n");
  EXPECT_EQ(fb->unit.pous.at(0)->extends, "Base");
  EXPECT_EQ(show(fb->unit.pous[0]->body), "{(:= x 1)}");
  EXPECT_EQ(diags("PROGRAM P : END_PROGRAM"),
            "1:11 E006 a PROGRAM has no return type; only a FUNCTION or METHOD has one\n"
            "1:13 E006 expected a type, found 'END_PROGRAM'\n");
}

// ---- Errors and recovery ----------------------------------------------------------------------

TEST(ParserErrors, ThreeErrorsThreeDiagnostics) {
  EXPECT_EQ(diags("PROGRAM P\n"
                  "VAR x : INT; END_VAR\n"
                  "x := 1\n"
                  "y := (2 + ;\n"
                  "IF x THEN z := 3 END_IF\n"
                  "w := 4;\n"
                  "END_PROGRAM\n"),
            "4:1 E006 expected ';' after statement, found 'y'\n"
            "4:11 E006 expected an expression, found ';'\n"
            "5:18 E006 expected ';' after statement, found 'END_IF'\n");
}

TEST(ParserErrors, MissingEndKeywords) {
  EXPECT_EQ(diags("PROGRAM P\nIF a THEN\n  x := 1;\nEND_PROGRAM\n"),
            "4:1 E007 expected 'END_IF' to close 'IF' at line 2, found 'END_PROGRAM'\n");
  EXPECT_EQ(diags("PROGRAM P\nWHILE a DO\n  IF b THEN x := 1;\nEND_WHILE\nEND_PROGRAM\n"),
            "4:1 E007 expected 'END_IF' to close 'IF' at line 3, found 'END_WHILE'\n");
  EXPECT_EQ(diags("PROGRAM P\nVAR x : INT;\nx := 1;\nEND_PROGRAM\n"),
            "3:1 E007 expected 'END_VAR' to close 'VAR' at line 2, found 'x'\n");
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nMETHOD M\nx := 1;\nMETHOD N\nEND_METHOD\nEND_FUNCTION_BLOCK\n"),
            "4:1 E007 expected 'END_METHOD' to close 'METHOD' at line 2, found 'METHOD'\n");
  EXPECT_EQ(diags("PROGRAM P\nx := 1;\n"), "3:1 E007 expected 'END_PROGRAM' to close 'PROGRAM' at line 1, found end of file\n");
}

TEST(ParserErrors, StrayEndKeywordsAreSkipped) {
  EXPECT_EQ(diags("PROGRAM P\nx := 1;\nEND_IF\ny := 2;\nEND_PROGRAM\n"),
            "3:1 E006 unexpected 'END_IF': there is no open IF\n");
  auto p = parse("PROGRAM P\nx := 1;\nEND_IF\ny := 2;\nEND_PROGRAM\n");
  EXPECT_EQ(show(p->unit.pous[0]->body), "{(:= x 1) (:= y 2)}");
}

TEST(ParserErrors, BadStatementsAndDeclarations) {
  EXPECT_EQ(diags("PROGRAM P\nx = 1;\nTHEN;\nEND_PROGRAM"),
            "2:3 E006 expected ':=' or a call in statement, found '='\n"
            "3:1 E006 expected a statement, found 'THEN'\n");
  EXPECT_EQ(diags("PROGRAM P\nVAR\n  a INT;\n  b : INT\n  c : ;\n  IF : INT;\nEND_VAR\nEND_PROGRAM"),
                "3:5 E006 expected ':' after variable name, found 'INT'\n"
                "5:3 E006 expected ';' after variable declaration, found 'c'\n"
                "5:7 E006 expected a type, found ';'\n"
                "6:3 E007 expected 'END_VAR' to close 'VAR' at line 2, found 'IF'\n"
                "6:6 E006 expected an expression, found ':'\n"
                "7:1 E007 expected 'END_IF' to close 'IF' at line 6, found 'END_VAR'\n");
}

TEST(ParserErrors, TopLevelGarbageAndMisplacedMembers) {
  EXPECT_EQ(diags("x := 1;\nPROGRAM P END_PROGRAM"),
            "1:1 E006 expected PROGRAM, FUNCTION, FUNCTION_BLOCK, INTERFACE, TYPE, VAR_GLOBAL or CONFIGURATION, found 'x'\n");
  EXPECT_EQ(diags("METHOD M END_METHOD\nPROGRAM P END_PROGRAM"),
            "1:1 E006 'METHOD' is only allowed inside a FUNCTION_BLOCK, PROGRAM or INTERFACE\n");
  auto p = parse("x := 1;\nPROGRAM P END_PROGRAM");
  EXPECT_EQ(p->unit.pous.size(), 1u);
}

// A run of tokens that make no sense where they are gets one error, then parsing resumes at the
// next statement, member or END keyword.
TEST(ParserErrors, FloodsGiveOneError) {
  EXPECT_EQ(diags("PROGRAM P\nTHEN 1 2 3 := := ) ) DO;\nx := 1;\nEND_PROGRAM"),
            "2:1 E006 expected a statement, found 'THEN'\n");
  EXPECT_EQ(diags("PROGRAM P\nx := 1;\nEND_VAR END_TYPE END_STRUCT END_VAR\ny := 2;\nEND_PROGRAM"),
            "3:1 E006 expected a statement, METHOD, PROPERTY, ACTION or 'END_PROGRAM', found 'END_VAR'\n");
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nMETHOD M\nEND_METHOD\nEND_VAR END_TYPE\nx := 1;\nEND_VAR\nEND_FUNCTION_BLOCK"),
            "4:1 E006 expected a statement, METHOD, PROPERTY, ACTION or 'END_FUNCTION_BLOCK', found 'END_VAR'\n"
            "6:1 E006 expected a statement, METHOD, PROPERTY, ACTION or 'END_FUNCTION_BLOCK', found 'END_VAR'\n");
  EXPECT_EQ(diags("FUNCTION_BLOCK F\nPROPERTY P : INT\nx := 1; y := 2;\nGET P := 1; END_GET\nEND_PROPERTY\nEND_FUNCTION_BLOCK"),
            "3:1 E006 expected GET, SET or END_PROPERTY, found 'x'\n");
  EXPECT_EQ(diags("INTERFACE I\nx := 1; y := 2;\nMETHOD M END_METHOD\nz := 3;\nEND_INTERFACE"),
            "2:1 E006 expected METHOD, PROPERTY or END_INTERFACE, found 'x'\n"
            "4:1 E006 expected METHOD, PROPERTY or END_INTERFACE, found 'z'\n");
  EXPECT_EQ(diags("CONFIGURATION C\nx := 1; y := 2;\nRESOURCE R ON PLC\na b c;\nEND_RESOURCE\nEND_CONFIGURATION"),
            "2:1 E006 expected VAR_GLOBAL, VAR_CONFIG, RESOURCE, TASK, PROGRAM or END_CONFIGURATION, found 'x'\n"
            "4:1 E006 expected VAR_GLOBAL, TASK, PROGRAM or END_RESOURCE, found 'a'\n");
  // The flood of a misplaced body (statements after a forgotten METHOD header) is one error too.
  auto p = parse("FUNCTION_BLOCK F\nMETHOD M\nEND_METHOD\nx := 1;\n) ) ) ;\ny := 2;\nEND_FUNCTION_BLOCK");
  EXPECT_EQ(diagText(p->diags), "5:1 E006 expected a statement, found ')'\n");
  EXPECT_EQ(show(p->unit.pous[0]->body), "{(:= x 1) (:= y 2)}");
}

TEST(ParserErrors, DeepNestingIsReportedNotACrash) {
  std::string deepParens = "PROGRAM P x := " + std::string(20000, '(') + "1" + std::string(20000, ')') + "; END_PROGRAM";
  std::string text = diags(deepParens);
  EXPECT_NE(text.find("E010 nesting too deep"), std::string::npos) << text;
  std::string deepIfs = "PROGRAM P ";
  for (int i = 0; i < 5000; ++i) deepIfs += "IF a THEN ";
  EXPECT_NE(diags(deepIfs).find("E010"), std::string::npos);
  std::string longChain = "PROGRAM P x := a";
  for (int i = 0; i < 20000; ++i) longChain += " + a";
  EXPECT_NE(diags(longChain + "; END_PROGRAM").find("E010"), std::string::npos);
  std::string members = "PROGRAM P x := a";
  for (int i = 0; i < 20000; ++i) members += ".b";
  EXPECT_NE(diags(members + "; END_PROGRAM").find("E010"), std::string::npos);
  std::string unary = "PROGRAM P x := " + std::string(20000, '-') + "1; END_PROGRAM";
  EXPECT_NE(diags(unary).find("E010"), std::string::npos);
  std::string pointers = "PROGRAM P VAR p : ";
  for (int i = 0; i < 5000; ++i) pointers += "POINTER TO ";
  EXPECT_NE(diags(pointers + "INT; END_VAR END_PROGRAM").find("E010"), std::string::npos);
  // A moderately nested but legal program parses fine.
  EXPECT_EQ(expr(std::string(100, '(') + "1" + std::string(100, ')')), "1");
}

TEST(ParserErrors, GarbageNeverCrashes) {
  std::mt19937 rng(42);
  std::vector<std::string> words = {"PROGRAM", "END_PROGRAM", "FUNCTION_BLOCK", "METHOD", "END_METHOD", "VAR", "END_VAR",
                                    "IF", "THEN", "ELSE", "END_IF", "CASE", "OF", "END_CASE", "FOR", "TO", "DO",
                                    "END_FOR", "x", "y", ":=", ":", ";", "(", ")", "[", "]", ",", "..", ".", "1",
                                    "T#1s", "'s'", "INT#", "#", "^", "+", "*", "NOT", "TYPE", "END_TYPE", "STRUCT",
                                    "PROPERTY", "GET", "END_GET", "CONFIGURATION", "RESOURCE", "TASK", "WITH", "=>",
                                    "{attribute 'a'}", "REPEAT", "UNTIL", "S=", "REF=", "%IX0.0", "ARRAY", "ELSIF"};
  for (int round = 0; round < 3000; ++round) {
    std::string text;
    size_t len = rng() % 40;
    for (size_t i = 0; i < len; ++i) text += words[rng() % words.size()] + (rng() % 3 ? " " : "\n");
    Diagnostics d;
    NodeId next = 0;
    parseFile(0, text, d, next);
  }
  std::string bytes;
  for (int i = 0; i < 20000; ++i) bytes += static_cast<char>(rng() % 256);
  Diagnostics d;
  NodeId next = 0;
  parseFile(0, bytes, d, next);
  SUCCEED();
}

}  // namespace
}  // namespace virtcom::st
