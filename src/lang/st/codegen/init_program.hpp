#pragma once
// The init program: CODESYS calls METHOD FB_init of every FB instance once, before the first
// scan. virtcom generates a POU (Module::initPou) that does so for every instance reachable
// from the globals and the program instances, nested instances before their container, with
// bInitRetains := TRUE and bInCopyCode := FALSE (a cold start) and the instance declaration's
// arguments (`inst : FB_T(a := 1)`) bound to FB_init's other inputs. Instances in a POU's frame
// get their calls at the start of every call instead (buildFrameInitCalls).
#include <memory>

#include "lang/st/declare/program_model.hpp"

namespace virtcom::st {

// The init program's AST (a PROGRAM named __INIT), or null when no instance has an FB_init.
std::unique_ptr<Pou> buildInitProgram(const ProgramModel& model, const TypeTable& types);
// The exit program (__EXIT, Module::exitPou): METHOD FB_exit of every such instance with
// bInCopyCode := FALSE, run once when the PLC program ends (CODESYS: before a new download or
// a reset), in the reverse order of FB_init. Null when no instance has an FB_exit. Instances
// in a frame get theirs at the end of every call instead (buildFrameExitCalls).
std::unique_ptr<Pou> buildExitProgram(const ProgramModel& model, const TypeTable& types);
// The FB_init calls for the instances among `pou`'s frame variables (VAR of a FUNCTION or
// METHOD, VAR_TEMP of any POU), run before its body: these are initialised on every call, so
// CODESYS calls their FB_init on every call too. Empty when none has an FB_init.
StmtList buildFrameInitCalls(const ProgramModel& model, const TypeTable& types, const PouSym& pou);
// The FB_exit calls for the same instances, in the reverse order, run when the call ends
// (after the body or a RETURN): the frame is given up then, as a stack frame is.
StmtList buildFrameExitCalls(const ProgramModel& model, const TypeTable& types, const PouSym& pou);

}  // namespace virtcom::st
