#pragma once
// The decomposition of seed 002 (section III.B): a checked diagram is cut into logic units (LU,
// one per ladder rung: the activities that feed it, the transitions between, the activities it
// drives), each unit gets its pattern type (lu_types.def), and each unit becomes one or more
// if-then rules, fired in order every scan.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lang/ad/diagram.hpp"

namespace virtcom::ad {

enum class LuType : uint8_t {
#define X(type, label, description) type,
#include "lang/ad/lu_types.def"
#undef X
};

std::string_view luTypeLabel(LuType type);        // "1", "2", "3", "4-1", "4-2"
std::string_view luTypeDescription(LuType type);

// One row of the LU table. Node and arc indexes point into the unit's Diagram.
struct LogicUnit {
  LuType type = LuType::Basic;
  std::vector<size_t> inputs;   // activities read, in the order their arcs are written
  std::vector<size_t> bars;     // logic-flow transitions, inputs before outputs
  std::vector<size_t> arcs;     // every arc of the unit, in the order written
  std::vector<size_t> outputs;  // activities written
};

// A rule's IF: activity states combined by the unit's joins. A Group names a join's value
// (the seed's `Group K := (C1=on OR L=on)`), computed before the rule that uses it.
struct Condition {
  enum class Kind : uint8_t { Term, Group, And, Or };
  Kind kind = Kind::Term;
  size_t node = 0;   // Term: the activity (timer and counter: their output Q); Group: the join
  bool on = true;    // Term: on (normal arc) or off (NOT-IN arc)
  std::vector<Condition> operands;  // And, Or
};

// A rule's THEN. For a normal activity: set it on (normal arc) or off (NOT-OUT arc) when the
// IF holds. For a timer or counter: drive its input with the IF, true or false, every scan:
// on = IN (timer), CU (CTU), CD (CTD); off (NOT-OUT, counters only) = RESET (CTU), LOAD (CTD).
struct RuleAction {
  size_t node = 0;
  bool on = true;
};

struct GroupDefinition {
  size_t bar = 0;
  Condition value;
};

struct Rule {
  std::string index;  // "3", or "3.1", "3.2" when a split de-groups unit 3 into several rules
  size_t unit = 0;    // index into DiagramTables::units
  std::vector<GroupDefinition> groups;  // computed first, each before those that use it
  Condition condition;
  std::vector<RuleAction> actions;
};

struct DiagramTables {
  const Diagram* diagram = nullptr;
  std::vector<LogicUnit> units;  // LU index = position + 1, in the order of their first arc
  std::vector<Rule> rules;       // in unit order: the firing order
};

// Decomposes a diagram that passed checkProgram (reader.hpp); arcs from start and to stop take
// part in no unit. Allocates; never fails on a checked diagram.
DiagramTables decompose(const Diagram& diagram);

}  // namespace virtcom::ad
