// Checks of assignment targets that emit nothing.
#include "lang/st/codegen/check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

// True if `p` is a variable of `pou` itself or of the FB instance it runs in.
bool isInsideOwnPou(const Place& p, const PouSym& pou) {
  if (!p.var) return false;
  for (const auto& l : pou.locals)
    if (&l == p.var) return true;
  const PouSym* owner = pou.kind == PouKind::FunctionBlock || pou.kind == PouKind::Program ? &pou : pou.owner;
  if (owner)
    for (const auto& m : owner->members)
      if (&m == p.var) return true;
  return false;
}

}  // namespace

bool checkAssignable(Diagnostics& diags, const Place& target, const PouSym& pou, SourceLocation loc) {
  if (target.constant) {
    diags.error(diag::E204, loc, "'" + (target.var ? target.var->name : std::string("value")) +
                                     "' is a CONSTANT and cannot be assigned");
    return false;
  }
  if (target.isInput && isInsideOwnPou(target, pou) && pou.kind == PouKind::FunctionBlock)
    diags.warning(diag::W304, loc, "writing the input '" + target.var->name +
                                       "' inside its own FUNCTION_BLOCK; the next call overwrites it");
  return true;
}

}  // namespace virtcom::st
