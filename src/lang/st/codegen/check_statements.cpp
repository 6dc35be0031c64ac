// Checks of statements that emit nothing: assignment targets, FOR control variables, CASE labels.
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
    diags.error(diag::E204, loc, target.var ? "'" + target.var->name + "' is a CONSTANT and cannot be assigned"
                                            : std::string("this is part of a CONSTANT and cannot be assigned"));
    return false;
  }
  if (target.isInput && isInsideOwnPou(target, pou) && pou.kind == PouKind::FunctionBlock)
    diags.warning(diag::W304, loc, "writing the input '" + target.var->name +
                                       "' inside its own FUNCTION_BLOCK; the next call overwrites it");
  return true;
}

bool checkForVariable(Diagnostics& diags, const TypeTable& types, const Place& var, SourceLocation loc) {
  if (!types.isInteger(var.type)) {
    diags.error(diag::E202, loc, "a FOR control variable must be an integer, found " + describe(types, var.type));
    return false;
  }
  if (var.constant) {
    diags.error(diag::E204, loc, "a CONSTANT cannot be a FOR control variable");
    return false;
  }
  return true;
}

void checkCaseLabel(Diagnostics& diags, const TypeTable& types, TypeId selector, const CaseLabelRange& label,
                    bool isRange, std::vector<CaseLabelRange>& seen) {
  for (const auto& prev : seen)
    if (label.lo <= prev.hi && label.hi >= prev.lo)
      diags.error(diag::E208, label.loc, "CASE label " + std::to_string(label.lo) +
                                             (isRange ? ".." + std::to_string(label.hi) : "") +
                                             " overlaps an earlier label (line " + std::to_string(prev.loc.line) + ")");
  seen.push_back(label);
  if (!types.isInteger(selector)) return;
  uint32_t bits = types.bits(selector);
  bool sgn = types.isSignedInt(selector);
  int64_t min = bits >= 64 ? INT64_MIN : sgn ? -(int64_t(1) << (bits - 1)) : 0;
  int64_t max = bits >= 64 ? INT64_MAX : sgn ? (int64_t(1) << (bits - 1)) - 1 : (int64_t(1) << bits) - 1;
  if (label.hi < min || label.lo > max)
    diags.warning(diag::W302, label.loc, "CASE label can never match a selector of type " + describe(types, selector));
}

}  // namespace virtcom::st
