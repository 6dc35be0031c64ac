#pragma once
// The Sequential Function Chart of one PROGRAM or FUNCTION_BLOCK body, as written (names
// unresolved, case preserved), whatever the notation: textual SFC (the ST parser fills it from
// INITIAL_STEP / STEP / TRANSITION / ACTION) or graphical SFC (the PLCopen XML importer fills it
// from steps, transitions, divergences, convergences, jumps and action blocks).
//
// How a producer fills it:
// - one Step per step (jumps are transitions whose `to` names an earlier step; a graphical
//   divergence or convergence becomes a transition with several `from` or `to` steps);
//   exactly one step of each network has initial = true (a network: the steps connected by
//   transitions; IEC 61131-3 allows several in one body, and they evolve side by side);
// - one Transition per transition: `from` / `to` list the steps it deactivates / activates
//   (several = simultaneous convergence / divergence); selective branches are several
//   transitions with the same source step, ordered by `priority` (lower value first; unset
//   after set ones, then in declaration order); the condition is either `condition` (an ST
//   expression) or `body` (ST statements that assign the BOOL result to the transition's name,
//   which must then be set);
// - actions are either the POU's ACTIONs (st::Pou::actions, the ST parser puts `ACTION ...
//   END_ACTION` there) or the chart's own `actions` (which lowerChart() moves into
//   st::Pou::actions); an association naming neither drives a BOOL variable of that name;
// - every location points at the element in its source file (diagnostics quote them).
//
// Then lowerChart() (lang/sfc/lower.hpp) checks the chart (unknown or duplicate steps, initial
// step, qualifiers, unsafe and unreachable structure) and turns it into ordinary ST: hidden
// variables and statements appended to the POU, so type checking, code generation, the VM,
// traces and protocol servers see plain variables.
//
// Dependencies: core and the ST syntax tree (lang/syntax/ast.hpp, header only); nothing else.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/source.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::sfc {

enum class Qualifier : uint8_t {
#define X(name, spelling, needsTime, description) name,
#include "lang/sfc/qualifiers.def"
#undef X
};

// "N", "SD", ...
std::string_view qualifierSpelling(Qualifier q);
// True for L, D, SD, DS, SL.
bool qualifierNeedsTime(Qualifier q);
// Case-insensitive; nullopt for an unknown spelling.
std::optional<Qualifier> qualifierFromText(std::string_view text);

struct NamedRef {
  std::string name;
  SourceLocation loc;
};

// `A(L, T#2s)` inside a step: action (or BOOL variable) A, qualifier L, duration T#2s.
struct ActionAssociation {
  NamedRef action;
  Qualifier qualifier = Qualifier::N;
  st::ExprPtr duration;   // a TIME expression; set exactly when qualifierNeedsTime(qualifier)
  NamedRef indicator;     // optional indicator variable (name empty if none): kept, no effect (IEC)
  SourceLocation loc;     // the qualifier
};

struct Step {
  std::string name;
  SourceLocation loc;
  bool initial = false;
  std::vector<ActionAssociation> actions;
};

struct Transition {
  std::string name;                  // may be empty unless `body` is used
  SourceLocation loc;
  std::optional<int64_t> priority;   // lower value = higher priority among a step's transitions
  std::vector<NamedRef> from;        // at least one step
  std::vector<NamedRef> to;          // at least one step
  st::ExprPtr condition;             // `:= expr;` form, or null if `body` is used
  st::StmtList body;                 // ST body form: assigns the result to `name`
};

// An action with an ST body defined with the chart (graphical SFC); textual ACTIONs are
// st::Pou::actions instead.
struct Action {
  std::string name;
  SourceLocation loc;
  st::StmtList body;
};

struct Chart {
  SourceLocation loc;   // the first element of the chart
  std::vector<Step> steps;
  std::vector<Transition> transitions;
  std::vector<Action> actions;
  bool empty() const { return steps.empty() && transitions.empty() && actions.empty(); }
};

}  // namespace virtcom::sfc
