#pragma once
// The variables of a program image a client sees at top level, by name.
#include <string>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::bc {

// In declaration order: the globals and every program instance's declared (not hidden) variables
// as "MAIN.x". A member bit (AT %QX0.3 in a program) has `bit` set and `address` at its byte.
// Shared by the ADS symbol table and the write audit. Allocates: not for the scan path.
struct NamedVar {
  std::string name;
  VarRef ref;
};
std::vector<NamedVar> listVariables(const Module& m);

}  // namespace virtcom::bc
