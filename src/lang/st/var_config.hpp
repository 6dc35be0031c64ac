#pragma once
// VAR_CONFIG (IEC 61131-3 2.7.1): a CONFIGURATION gives the located variables a program
// declares with an incomplete address (`x AT %IX* : BOOL;`) their address
// (`VAR_CONFIG p.x AT %IX1.0 : BOOL; END_VAR`). Applied to the syntax tree before the
// declaration stage, so a completed variable is declared exactly like one located in place.
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::st {

// Writes every VAR_CONFIG address (and initial value) into the program's declaration; E201 for
// an unknown instance or variable, E109 for an entry that does not complete a `*` address of
// the same area and type, or a PROGRAM type whose instances would need different addresses.
void applyVarConfig(std::vector<CompilationUnit>& units, Diagnostics& diags);

}  // namespace virtcom::st
