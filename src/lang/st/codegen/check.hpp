#pragma once
// The checks of code generation that emit nothing: argument binding and counting, method
// access, writability of assignment targets, relations between FB and interface types. Each
// reports its diagnostics (E2xx, W3xx) and says whether emission may go on; none touches the
// module. The checks that need a value first (types of expressions, constants) stay with the
// emitters that compute the value (codegen_*.cpp, builtin_*.cpp).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/st/codegen/codegen.hpp"
#include "lang/st/declare/standard_functions.hpp"

namespace virtcom::st {

// --- standard functions (check_arguments.cpp) ---

// The arguments of the standard function call `call` in parameter order: positional ones where
// they stand, named ones by their IEC names (`naming`, `listed`). Nullopt after E203 for an
// output, an unknown name, an input given twice or a gap.
std::optional<std::vector<const Expr*>> orderStandardArguments(Diagnostics& diags, const std::string& name,
                                                               ParameterNaming naming, std::string_view listed,
                                                               const Expr& call);
// False after E203 if `count` is outside fn's argument range.
bool checkArgumentCount(Diagnostics& diags, const StandardFunction& fn, SourceLocation loc, size_t count);

// --- calls of POUs (check_calls.cpp) ---

// Binds the arguments of `call` to `params` of `callee` (positional in declaration order, or
// by name; never both), one Binding per argument in the order written. False after E203 for
// mixed forms, too many, unknown, repeated or wrongly connected arguments, a missing input of
// a function called positionally, or an unconnected VAR_IN_OUT of a function or method.
bool bindArguments(Diagnostics& diags, const Expr& call, const std::vector<const VarInfo*>& params, PouSym* callee,
                   std::vector<PouCompiler::Binding>& out);
// The variable `actual` passed to VAR_IN_OUT (or REFERENCE TO input) `param`, which wants a
// `wanted`: false after E202 (another type; a derived FB and any string length are fine), E204
// (a CONSTANT, unless the parameter is VAR_IN_OUT CONSTANT) or E203 (a single bit).
bool checkInOutActual(Diagnostics& diags, const ProgramModel& m, const TypeTable& types, const VarInfo& param,
                      TypeId wanted, const Place& actual, SourceLocation loc);
// PRIVATE methods are callable inside their FB only, PROTECTED ones in derived FBs too; false
// after E216. `caller` is the POU whose body makes the call.
bool checkMethodAccess(Diagnostics& diags, const PouSym& caller, const PouSym& method, SourceLocation loc);

// --- statements (check_statements.cpp) ---

// False after E204 if `target` is a CONSTANT; W304 when an FB writes its own input.
bool checkAssignable(Diagnostics& diags, const Place& target, const PouSym& pou, SourceLocation loc);
// False after E202 (not an integer) or E204 (a CONSTANT) for the control variable of a FOR.
bool checkForVariable(Diagnostics& diags, const TypeTable& types, const Place& var, SourceLocation loc);

// The values lo..hi of one CASE label (lo == hi for a single value) and where it is written.
struct CaseLabelRange {
  int64_t lo;
  int64_t hi;
  SourceLocation loc;
};
// Reports E208 for each earlier label in `seen` that `label` overlaps, then adds it to `seen`;
// W302 if no value of the integer type `selector` can match it. `isRange`: written as lo..hi.
void checkCaseLabel(Diagnostics& diags, const TypeTable& types, TypeId selector, const CaseLabelRange& label,
                    bool isRange, std::vector<CaseLabelRange>& seen);

// --- type relations (check_types.cpp) ---

// The type two operands of an operator are computed in (IEC widening; an untyped literal takes
// the other side's type; a REAL literal with an integer gives REAL; signed with unsigned gives
// the signed type one rank up); kNoType if they do not combine.
TypeId commonType(const TypeTable& types, const Value& a, const Value& b);

// True if FB `c` is `base` or EXTENDS it (directly or further up).
bool derivesFrom(const PouSym* c, const PouSym* base);
// The types are equal, or both FBs and `actual` EXTENDS `wanted` (directly or further up).
bool sameOrDerivedFb(const ProgramModel& m, TypeId actual, TypeId wanted);
// Interface and class names are upper-cased. True if interface `itf` is `target` or extends it.
bool interfaceExtends(const ProgramModel& m, const std::string& itf, const std::string& target);
// True if FB `c` or one of its bases implements `itf` or an interface extending it.
bool implementsInterface(const ProgramModel& m, const PouSym* c, const std::string& itf);

}  // namespace virtcom::st
