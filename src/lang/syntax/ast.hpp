#pragma once
// The syntax tree of Structured Text, exactly as written (names unresolved, case preserved).
// The parser builds it; later passes never edit it but keep side tables keyed by node id.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/source.hpp"
#include "lang/syntax/ladder.hpp"

namespace virtcom::sfc {
struct Chart;  // lang/sfc/sfc_model.hpp
}

namespace virtcom::st {

using NodeId = uint32_t;

struct Expr;
struct Stmt;
struct TypeSpec;
using ExprPtr = std::unique_ptr<Expr>;
using StmtPtr = std::unique_ptr<Stmt>;
using StmtList = std::vector<StmtPtr>;
using TypeSpecPtr = std::unique_ptr<TypeSpec>;

// `{attribute 'name' := 'value'}` pragmas written before a declaration.
struct Attribute {
  std::string name;
  std::string value;
};

// ---- Types as written -------------------------------------------------------------------
enum class TypeSpecKind : uint8_t {
  Named,      // INT, MyStruct, TON, MyEnum (elementary names are Named too; resolved later)
  String,     // STRING / STRING(n) / STRING[n]; WSTRING with wide = true
  Array,      // ARRAY [lo..hi, ...] OF element
  Pointer,    // POINTER TO element
  Reference,  // REFERENCE TO / REF_TO element
  Subrange,   // base (lo..hi), e.g. INT (0..100)
  Enum,       // (a, b := 5, c) [base type name in `name`, may be empty]
  Struct,     // STRUCT fields END_STRUCT or UNION fields END_UNION (only inside TYPE; `name` holds EXTENDS base, may be empty)
};

struct VarDecl;

struct EnumValueDecl {
  std::string name;
  ExprPtr value;  // null: previous + 1 (first: 0)
  SourceLocation loc;
};

struct ArrayRange {
  ExprPtr lo;
  ExprPtr hi;
};

struct TypeSpec {
  TypeSpecKind kind = TypeSpecKind::Named;
  SourceLocation loc;
  std::string name;               // Named: type name; Enum: base type; Struct: EXTENDS base
  bool wide = false;              // String: WSTRING
  ExprPtr length;                 // String: declared length (null: default 80)
  std::vector<ArrayRange> dims;   // Array
  TypeSpecPtr element;            // Array / Pointer / Reference element; Subrange base
  ExprPtr lo, hi;                 // Subrange
  std::vector<EnumValueDecl> enumValues;  // Enum
  std::vector<VarDecl> fields;    // Struct
  bool isUnion = false;           // Struct written as UNION ... END_UNION: every field at offset 0
};

// ---- Expressions ------------------------------------------------------------------------
enum class ExprKind : uint8_t {
  IntLit,      // intValue (magnitude; sign is a Unary Neg), typePrefix optional (INT#5)
  RealLit,     // realValue, typePrefix optional
  BoolLit,     // intValue 0/1, typePrefix optional (BOOL#1)
  StringLit,   // text = decoded bytes; wide for "..." (WSTRING)
  TimeLit,     // intValue = nanoseconds; typePrefix "TIME" or "LTIME"
  DateLit,     // intValue = seconds since 1970 (DATE/DT) or ms since midnight (TOD); typePrefix DATE/TOD/DT
  EnumLit,     // typePrefix = enum type, text = value name (Color#Red)
  Name,        // text = identifier
  This,        // THIS  (THIS^ is Deref(This))
  Super,       // SUPER (SUPER^ is Deref(Super))
  Member,      // lhs.text
  BitAccess,   // lhs.intValue (w.3; %X3 form gives the same)
  Index,       // lhs[items...]
  Deref,       // lhs^
  Unary,       // op lhs
  Binary,      // lhs op rhs
  Call,        // lhs(args)
  ArrayInit,   // [items...]; an item may be a Repeat
  Repeat,      // intValue (count) ( lhs )   -- only inside ArrayInit: 3(0)
  StructInit,  // (name := value, ...) in args (named, no outputs)
  DirectAddr,  // %IX0.0, %QW2, %MD4: text = the address as written
};

enum class UnaryOp : uint8_t { Neg, Plus, Not };
enum class BinaryOp : uint8_t {
  Power, Mul, Div, Mod, Add, Sub,
  Lt, Le, Gt, Ge, Eq, Ne,
  And, Xor, Or,
  AndThen, OrElse,
};

struct CallArg {
  std::string name;      // empty: positional
  bool output = false;   // name => variable
  bool negated = false;  // NOT name => variable (CODESYS allows inverting an output)
  ExprPtr value;         // for outputs: the receiving variable (may be null: `Q =>`)
  SourceLocation loc;
};

struct Expr {
  ExprKind kind = ExprKind::Name;
  SourceLocation loc;
  NodeId id = 0;
  UnaryOp unaryOp = UnaryOp::Neg;
  BinaryOp binaryOp = BinaryOp::Add;
  bool wide = false;
  uint64_t intValue = 0;
  double realValue = 0;
  std::string text;
  std::string typePrefix;
  ExprPtr lhs, rhs;
  std::vector<ExprPtr> items;   // Index: subscripts; ArrayInit: elements
  std::vector<CallArg> args;    // Call; StructInit (named values)
};

// ---- Statements -------------------------------------------------------------------------
enum class StmtKind : uint8_t {
  Assign,     // lhs := rhs
  RefAssign,  // lhs REF= rhs
  AttemptAssign,  // lhs ?= rhs (IEC 61131-3 ed. 3 assignment attempt)
  SetAssign,  // lhs S= rhs (CODESYS)
  ResetAssign,// lhs R= rhs (CODESYS)
  Call,       // expr (a Call expression used as a statement)
  If,         // branches (cond + body), elseBody
  Case,       // expr selector, cases, elseBody
  For,        // lhs control variable, from = rhs, to, by (may be null), body
  While,      // expr cond, body
  Repeat,     // body, expr cond
  Exit,
  Continue,
  Return,
  Empty,
  Jump,       // JMP label; (CODESYS): label names the target
  Label,      // label: (marks the position of the next statement in its list)
};

struct CondBlock {
  ExprPtr cond;
  StmtList body;
  SourceLocation loc;
};

struct CaseLabel {
  ExprPtr lo;
  ExprPtr hi;  // null unless a range lo..hi
};

struct CaseBranch {
  std::vector<CaseLabel> labels;
  StmtList body;
  SourceLocation loc;
};

// What a statement is to PLC code coverage (docs/coverage.md). The user's statements count by
// line; those a lowering generated (an SFC's bookkeeping) do not, except the one that marks a
// step's activation or a transition's firing, which counts under the element's name. An
// activity-diagram rule's `IF __ad_fired[k] THEN ... END_IF` is RuleFired: entering its THEN
// counts as the rule's firing (no branch probes); with an empty THEN (a rule that only drives
// blocks) it is compiled only when coverage is on, so it costs nothing otherwise.
enum class CoverRole : uint8_t { Source, Generated, StepActivated, TransitionFired, RuleFired };

struct Stmt {
  StmtKind kind = StmtKind::Empty;
  SourceLocation loc;
  NodeId id = 0;
  ExprPtr lhs, rhs, expr, to, by;
  std::vector<CondBlock> branches;
  std::vector<CaseBranch> cases;
  StmtList body;
  StmtList elseBody;
  bool hasElse = false;
  std::string label;        // Jump, Label: the label's name as written
  CoverRole cover = CoverRole::Source;
  std::string coverName;    // StepActivated, TransitionFired: the step's or transition's name;
                            // RuleFired: the rule's index
  SourceLocation coverLoc;  // ... and where the chart declares it (the rule: the arc to its first output)
};

// ---- Declarations -----------------------------------------------------------------------
enum class VarSection : uint8_t { Var, Input, Output, InOut, Temp, Global, External, Inst, Stat };

struct DeclName {
  std::string name;
  SourceLocation loc;
};

// `start : BOOL R_EDGE;` (IEC 61131-3 edge-detecting input): inside the FB the input reads
// TRUE only on the call where it rose (fell).
enum class EdgeKind : uint8_t { None, Rising, Falling };

struct VarDecl {
  std::vector<DeclName> names;   // a, b, c : T;
  TypeSpec type;
  ExprPtr init;                  // := value (may be an ArrayInit or StructInit)
  std::string location;          // AT %IX0.0 -> "%IX0.0"; empty if not located
  std::vector<CallArg> fbInitArgs;  // inst : FB_T(a := 1) -- FB_init-style arguments
  std::vector<Attribute> attributes;
  SourceLocation loc;
  EdgeKind edge = EdgeKind::None;  // R_EDGE / F_EDGE after the type
  SourceLocation edgeLoc;
};

struct VarBlock {
  VarSection section = VarSection::Var;
  bool constant = false;
  bool retain = false;
  bool persistent = false;
  std::vector<VarDecl> vars;
  SourceLocation loc;
};

enum class Access : uint8_t { Default, Public, Private, Protected, Internal };

enum class PouKind : uint8_t { Program, Function, FunctionBlock, Method, Action, PropertyGet, PropertySet };

struct Pou;

struct Property {
  std::string name;
  SourceLocation loc;
  Access access = Access::Default;
  bool isAbstract = false;
  bool isFinal = false;
  TypeSpec type;
  std::unique_ptr<Pou> getter;  // may be null
  std::unique_ptr<Pou> setter;  // may be null
};

// A body written as a chart (textual or graphical SFC), kept as written, and what its lowering
// (lang/sfc/lower.hpp) added to the POU: the statements, variable blocks and actions in these
// index ranges implement the chart, all others are the POU's own (bodies imported after the
// chart come after the range). The exporter writes the chart instead of the ranges.
struct ChartSource {
  struct Range {
    size_t begin = 0, end = 0;
    bool contains(size_t i) const { return i >= begin && i < end; }
  };
  std::shared_ptr<const sfc::Chart> chart;
  Range statements, varBlocks, actions;
};

struct Pou {
  PouKind kind = PouKind::Program;
  std::string name;
  SourceLocation loc;
  SourceLocation endLoc;         // the END_xxx keyword
  Access access = Access::Default;
  bool isAbstract = false;
  bool isFinal = false;
  bool hasReturnType = false;
  TypeSpec returnType;           // FUNCTION / METHOD ... : T
  std::string extends;           // FUNCTION_BLOCK A EXTENDS B
  std::vector<std::string> implements;
  std::vector<VarBlock> varBlocks;
  StmtList body;
  bool hasBody = false;          // false for abstract/interface methods
  std::vector<std::unique_ptr<Pou>> methods;
  std::vector<std::unique_ptr<Pou>> actions;
  std::vector<Property> properties;
  std::vector<Attribute> attributes;
  std::optional<ChartSource> chart;  // set when the body is a lowered chart
  std::optional<Ladder> ladder;      // set when the body was lowered from ladder rungs (ladder.hpp)
};

struct Interface {
  std::string name;
  SourceLocation loc;
  std::vector<std::string> extends;
  std::vector<std::unique_ptr<Pou>> methods;   // no bodies
  std::vector<Property> properties;            // getters/setters without bodies
};

struct TypeDecl {
  std::string name;
  SourceLocation loc;
  TypeSpec spec;
  ExprPtr init;   // TYPE Level : INT (0..100) := 50; END_TYPE
  std::vector<Attribute> attributes;
};

struct GlobalVarList {
  std::string name;            // from the file name (GVL.st -> GVL); may be empty
  std::vector<VarBlock> blocks;
  std::vector<Attribute> attributes;
  SourceLocation loc;
};

struct TaskDecl {
  std::string name;
  SourceLocation loc;
  std::vector<CallArg> settings;  // INTERVAL := T#10ms, PRIORITY := 1, SINGLE := x
};

struct ProgramConfig {
  std::string instanceName;
  std::string taskName;          // empty: no WITH
  std::string typeName;
  std::vector<CallArg> args;
  SourceLocation loc;
};

struct Resource {
  std::string name;
  std::string onName;            // ON PLC
  SourceLocation loc;
  std::vector<VarBlock> globals;
  std::vector<TaskDecl> tasks;
  std::vector<ProgramConfig> programs;
};

// One VAR_CONFIG entry: `Cpu.p.x AT %IX1.0 : BOOL := TRUE;` (lang/st/var_config.hpp).
struct ConfigVar {
  std::vector<std::string> path;  // [resource.]instance.variable
  std::string location;           // "%IX1.0"
  TypeSpec type;
  ExprPtr init;                   // null: none
  SourceLocation loc;
};

struct Configuration {
  std::string name;
  SourceLocation loc;
  std::vector<VarBlock> globals;
  std::vector<Resource> resources;
  std::vector<ConfigVar> configVars;
};

// One parsed source file.
struct CompilationUnit {
  uint32_t fileId = 0;
  std::vector<std::unique_ptr<Pou>> pous;
  std::vector<Interface> interfaces;
  std::vector<TypeDecl> types;
  std::vector<GlobalVarList> globals;
  std::vector<Configuration> configurations;
};

}  // namespace virtcom::st
