#pragma once
// A scenario's conditions (docs/scenarios.md "Conditions"): `MAIN.x >= 3 AND NOT Robot1.busy`
// over PLC variables, device signals and world facts. Parsed once against a loaded cell, names
// resolved to addresses, tags and fact ids; evaluated on every scan as a small postfix program on
// a fixed stack: no string lookup, no allocation.
//
//   expr    := xor { OR xor }          xor := and { XOR and }       and := unary { AND unary }
//   unary   := NOT unary | compare     compare := operand [ (= <> < <= > >= == !=) operand ]
//   operand := ( expr ) | number | TRUE | FALSE | name
// A name is a device signal (`Robot1.busy`), a world fact (`world.pin1Placed`) or an elementary
// PLC variable (`MAIN.state`, `MAIN.errorIn[3]`), tried in that order. Keywords in any case.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/tag_bus.hpp"
#include "plant/world.hpp"

namespace virtcom::scenario {

// What a condition reads, as the running cell has it.
struct ValueSources {
  const uint8_t* plcMemory = nullptr;  // null without a soft PLC
  const TagBus* bus = nullptr;
  const plant::World* world = nullptr;
};

// What a condition may name: the loaded cell's program (null: none), bus and world.
struct NameScope {
  const bc::Module* module = nullptr;
  const TagBus* bus = nullptr;
  plant::World* world = nullptr;
};

class Expression {
 public:
  static constexpr size_t kMaxDepth = 16;  // operand stack; deeper expressions are rejected

  bool valid() const { return !code_.empty(); }
  const std::string& text() const { return text_; }
  // True if the condition holds now; false for an invalid expression. Allocates nothing.
  bool holds(const ValueSources& in) const { return evaluate(in) != 0; }
  double evaluate(const ValueSources& in) const;
  // The operands' values now, for a failure message: "MAIN.x = 2, Robot1.busy = TRUE".
  std::string describeOperands(const ValueSources& in) const;

  // Parses `text` (written at `loc`); reports mistakes at their column (code C061).
  static Expression parse(const std::string& text, SourceLocation loc, const NameScope& scope, Diagnostics& diags);

  enum class OpKind : uint8_t { Const, Var, Tag, Fact, Not, And, Or, Xor, Eq, Ne, Lt, Le, Gt, Ge };
  struct Operand {
    std::string name;
    uint32_t address = 0;  // Var: in PLC memory; Tag: tag id; Fact: fact id
    int8_t bit = -1;
    ElemType type = ElemType::Bool;
  };
  struct Op {
    OpKind kind = OpKind::Const;
    uint32_t operand = 0;  // Var/Tag/Fact: index into operands_
    double value = 0;      // Const
  };

 private:
  friend class ExpressionParser;
  double load(const Operand& o, OpKind kind, const ValueSources& in) const;

  std::string text_;
  std::vector<Op> code_;
  std::vector<Operand> operands_;
};

}  // namespace virtcom::scenario
