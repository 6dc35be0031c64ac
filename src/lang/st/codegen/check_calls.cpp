// Checks of POU calls that emit nothing: binding the arguments to the parameters, and whether a
// METHOD may be called from here.
#include <set>

#include "lang/st/codegen/check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

// IEC and CODESYS spell some standard FB inputs differently; both are accepted.
std::string canonicalParam(const PouSym* callee, const std::string& upperName) {
  if (!callee || !callee->isLibrary) return upperName;
  struct Alias {
    const char* fb;
    const char* iec;
    const char* codesys;
  };
  static const Alias kAliases[] = {{"CTU", "R", "RESET"},  {"CTD", "LD", "LOAD"}, {"CTUD", "R", "RESET"},
                                   {"CTUD", "LD", "LOAD"}, {"SR", "S1", "SET1"},  {"SR", "R", "RESET"},
                                   {"RS", "S", "SET"},     {"RS", "R1", "RESET1"}};
  std::string fb = upper(callee->name);
  if (fb.rfind("CT", 0) == 0) fb = fb.substr(0, fb.find('_'));  // the typed counters: CTU_DINT is a CTU
  for (const auto& a : kAliases)
    if (fb == a.fb && upperName == a.iec) return a.codesys;
  return upperName;
}

}  // namespace

bool bindArguments(Diagnostics& diags, const Expr& call, const std::vector<const VarInfo*>& params, PouSym* callee,
                   std::vector<PouCompiler::Binding>& out) {
  std::set<size_t> used;
  size_t positional = 0;
  bool ok = true;
  std::string calleeName = callee ? callee->qualifiedName : "?";
  bool anyNamed = false, anyPositional = false;
  for (const auto& arg : call.args) (arg.name.empty() ? anyPositional : anyNamed) = true;
  if (anyNamed && anyPositional) {
    diags.error(diag::E203, call.loc, "the call of '" + calleeName + "' mixes positional and named arguments; use one form");
    return false;
  }
  for (const auto& arg : call.args) {
    size_t index = params.size();
    if (arg.name.empty()) {
      // positional: inputs and in-outs in declaration order
      while (positional < params.size() && params[positional]->section == VarSection::Output) ++positional;
      index = positional++;
      if (index >= params.size()) {
        diags.error(diag::E203, arg.loc, "too many arguments for '" + calleeName + "' (it takes " +
                                             std::to_string(params.size()) + ")");
        ok = false;
        continue;
      }
    } else {
      std::string key = canonicalParam(callee, upper(arg.name));
      for (size_t i = 0; i < params.size(); ++i)
        if (upper(params[i]->name) == key) index = i;
      if (index == params.size()) {
        diags.error(diag::E203, arg.loc, "'" + calleeName + "' has no parameter '" + arg.name + "'");
        ok = false;
        continue;
      }
    }
    const VarInfo& p = *params[index];
    if (!used.insert(index).second) {
      diags.error(diag::E203, arg.loc, "parameter '" + p.name + "' is given twice");
      ok = false;
      continue;
    }
    if (arg.output != (p.section == VarSection::Output)) {
      diags.error(diag::E203, arg.loc, p.section == VarSection::Output
                                           ? "'" + p.name + "' is an output: connect it with '=>'"
                                           : "'" + p.name + "' is an input: pass it with ':='");
      ok = false;
      continue;
    }
    PouCompiler::Binding b;
    b.param = index;
    b.arg = &arg;
    out.push_back(b);
  }
  bool isFunction = callee && callee->kind == PouKind::Function;
  for (size_t i = 0; i < params.size(); ++i)
    if (isFunction && anyPositional && params[i]->section == VarSection::Input && !used.count(i) &&
        !(params[i]->decl && params[i]->decl->init)) {
      diags.error(diag::E203, call.loc, "too few arguments for '" + calleeName + "': input '" + params[i]->name + "' is missing");
      ok = false;
      break;
    }
  for (size_t i = 0; i < params.size(); ++i)
    if (params[i]->section == VarSection::InOut && !used.count(i) && callee && callee->kind != PouKind::FunctionBlock) {
      diags.error(diag::E203, call.loc, "VAR_IN_OUT '" + params[i]->name + "' of '" + calleeName + "' must be connected");
      ok = false;
    }
  return ok;
}

bool checkInOutActual(Diagnostics& diags, const ProgramModel& m, const TypeTable& types, const VarInfo& param,
                      TypeId wanted, const Place& actual, SourceLocation loc) {
  const bool readOnly = param.byReference && param.constant;
  // A derived FB instance may be passed for its base, as CODESYS allows: its layout starts
  // with the base's members, and methods dispatch on its class id.
  if (!sameOrDerivedFb(m, actual.type, wanted) && !(types.isString(actual.type) && types.isString(wanted))) {
    diags.error(diag::E202, loc, "'" + param.name + "' needs a " + describe(types, wanted) + " variable, found " +
                                     describe(types, actual.type));
    return false;
  }
  if (actual.constant && !readOnly) {
    diags.error(diag::E204, loc, "the CONSTANT '" + (actual.var ? actual.var->name : std::string("value")) +
                                     "' cannot be passed to '" + param.name + "', which may write it");
    return false;
  }
  if (actual.bit >= 0 || actual.valueBit >= 0) {
    diags.error(diag::E203, loc, "a single bit cannot be passed to VAR_IN_OUT '" + param.name + "'");
    return false;
  }
  return true;
}

bool checkMethodAccess(Diagnostics& diags, const PouSym& pou, const PouSym& method, SourceLocation loc) {
  Access access = method.ast->access;
  if (access != Access::Private && access != Access::Protected) return true;
  const PouSym* caller = pou.kind == PouKind::FunctionBlock ? &pou : pou.owner;
  const PouSym* owner = method.owner;
  bool allowed = caller == owner;
  // PROTECTED: from the declaring FB and FBs derived from it. The method may be the override of
  // a derived FB that a base FB's code dispatches to (a template method calling an ABSTRACT
  // step), so the caller may also be a base of the method's owner.
  if (access == Access::Protected) {
    for (const PouSym* c = caller; c && !allowed; c = c->base) allowed = c == owner;
    for (const PouSym* o = owner; o && !allowed; o = o->base) allowed = o == caller;
  }
  if (!allowed)
    diags.error(diag::E216, loc, "METHOD " + method.qualifiedName + " is " +
                                     (access == Access::Private ? "PRIVATE" : "PROTECTED") + " and cannot be called from here");
  return allowed;
}

}  // namespace virtcom::st
