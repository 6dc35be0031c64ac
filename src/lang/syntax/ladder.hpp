#pragma once
// A body as ladder rungs (IEC 61131-3 LD), for front ends whose model is naturally a ladder (the
// rule table of an activity diagram: one rung per rule, lang/ad). The front end lowers the
// rungs to statements as usual and keeps them on the POU (st::Pou::ladder), so the PLCopen
// exporter writes an LD body that vendor tools open as ladder instead of the lowered ST.
#include <cstdint>
#include <string>
#include <vector>

namespace virtcom::st {

// A rung's contact network: contacts in series (AND) and parallel branches (OR).
struct LadderCondition {
  enum class Kind : uint8_t { Contact, Series, Parallel };
  Kind kind = Kind::Contact;
  std::string variable;  // Contact: the BOOL it reads (a name, GVL.x, T.Q, %IX0.0)
  bool negated = false;  // Contact: normally closed
  std::vector<LadderCondition> operands;  // Series, Parallel
};

// What the rung's power drives, in order: coils (normal: the power; negated: its inverse;
// set / reset: latch on / off while powered) and function blocks called with the power on one
// input (a timer's IN, a counter's CU) and, optionally, a constant on another (PT, PV).
struct LadderOutput {
  enum class Kind : uint8_t { Coil, NegatedCoil, SetCoil, ResetCoil, Block };
  Kind kind = Kind::Coil;
  std::string variable;    // coils: the BOOL written; Block: the instance
  std::string blockType;   // Block: TON, CTU, ...
  std::string powerInput;  // Block: the input the rung drives (IN, CU, CD)
  std::string stateOutput = "Q";             // Block: the output drawn on to the right rail
  std::string constantInput, constantValue;  // Block: PT := T#5s, PV := 3; empty: none
};

struct LadderRung {
  std::string comment;  // shown above the rung: "Rule 3", "Group K"
  LadderCondition condition;
  std::vector<LadderOutput> outputs;
};

struct Ladder {
  std::vector<LadderRung> rungs;
};

}  // namespace virtcom::st
