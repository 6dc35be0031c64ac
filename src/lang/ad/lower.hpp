#pragma once
// Activity diagrams to the shared syntax tree, so they compile to the same bytecode as ST with
// no second runtime. The file's program becomes one PROGRAM; each diagram (function) one ACTION
// of it, called by the PROGRAM's body in file order; each rule of a diagram's rule table becomes
// the statements that fire it, in rule order.
#include <cstdint>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/ad/diagram.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::ad {

// The hidden `ARRAY [1..rules] OF BOOL` of the PROGRAM: element k is TRUE while the IF of the
// k-th rule of the file (diagrams in file order, rules in rule order) holds, set every scan as
// the rule is checked. `virtcom exec --trace-rules` reads it (rule_trace.hpp).
inline constexpr std::string_view kFiredVariable = "__ad_fired";

// The PROGRAM of a checked program (reader.hpp):
// - VAR: every port as a BOOL (`AT %IX0.0` when located), every timer and counter as an
//   instance of its block, every grouped join as a BOOL, so all are readable as PROGRAM.name;
// - per rule: its groups assigned (`K := C1 OR L;`), its fired flag `__ad_fired[k] := <IF>;`,
//   then for normal activities `IF __ad_fired[k] THEN Y := TRUE (FALSE for NOT-OUT); END_IF`
//   (the IF is there for every rule, empty without such writes: its THEN is the rule's firing
//   to code coverage, at the line of the arc to the rule's first output; an empty one is only
//   compiled with coverage), for timers `T(IN := __ad_fired[k], PT := preset)` and counters
//   `C(CU|CD := ..., PV := preset)` / `C.RESET|LOAD := __ad_fired[k]` every scan; these
//   statements do not count as lines to coverage, the call of each diagram's ACTION does;
// - per diagram ACTION, its rules as ladder rungs (st::Pou::ladder, ladder.hpp) for the LD export.
// The scan is the seed's: inputs are read before the rules (the PLC's input image), every rule
// is checked in order and sees what earlier rules wrote, outputs go out after the last rule.
// Nodes carry the location of the element or arc they come from. Allocates; never throws.
st::CompilationUnit lowerProgram(const Program& program, uint32_t fileId, st::NodeId& nextNodeId);

// A compiler front end (st::FrontEnd) for .ad files: readProgram, then lowerProgram if the file
// had no error (an empty unit otherwise).
st::CompilationUnit importDiagrams(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId);

// The same for AD-XML files (.adxml): readXmlProgram, then lowerProgram.
st::CompilationUnit importXmlDiagrams(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId);

}  // namespace virtcom::ad
