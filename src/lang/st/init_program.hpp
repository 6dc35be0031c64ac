#pragma once
// The init program: CODESYS calls METHOD FB_init of every FB instance once, before the first
// scan. virtcom generates a POU (Module::initPou) that does so for every instance reachable
// from the globals and the program instances, nested instances before their container, with
// bInitRetains := TRUE and bInCopyCode := FALSE (a cold start) and the instance declaration's
// arguments (`inst : FB_T(a := 1)`) bound to FB_init's other inputs.
#include <memory>

#include "lang/st/program_model.hpp"

namespace virtcom::st {

// The init program's AST (a PROGRAM named __INIT), or null when no instance has an FB_init.
std::unique_ptr<Pou> buildInitProgram(const ProgramModel& model, const TypeTable& types);

}  // namespace virtcom::st
