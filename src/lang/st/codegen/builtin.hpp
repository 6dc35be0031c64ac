#pragma once
// The emitters of the IEC standard functions, one per StandardFamily (builtin_*.cpp), and what
// they share. PouCompiler::builtin() has bound and counted the arguments (check_arguments.cpp);
// an emitter type-checks the values, reports E202/E108/E214 and emits the code.
#include <string>
#include <vector>

#include "lang/st/codegen/codegen.hpp"
#include "lang/st/declare/standard_functions.hpp"

namespace virtcom::st {

// The capacity of the strings the standard functions return (STRING(255), WSTRING(255)).
inline constexpr uint32_t kStringResultLength = 255;

// One call of a standard function, its arguments in parameter order and all present.
struct BuiltinCall {
  PouCompiler& pc;
  const StandardFunction& fn;
  const Expr& call;
  const std::vector<const Expr*>& args;
  TypeId expected;  // the type the context wants, or kNoType

  std::string name() const { return std::string(fn.name); }
  size_t count() const { return args.size(); }
  SourceLocation loc() const { return call.loc; }
  TypeTable& types() const { return pc.types(); }
  Diagnostics& diags() const { return pc.diags(); }
  // Input i evaluated, with `hint` as its expected type.
  Value arg(size_t i, TypeId hint = kNoType) const { return pc.expr(*args[i], hint); }
  // `v` coerced to DINT, in a register (lengths, positions, shift counts).
  uint16_t dint(Value v) const { return pc.toReg(pc.coerce(v, TypeTable::elem(ElemType::Dint), call.loc)); }
};

#define FAMILY(Name, what) Value emit##Name(BuiltinCall& call);
#include "lang/st/declare/standard_functions.def"

// A binary-operator node at `loc` with no operands, for the operator code paths.
Expr operatorExpr(BinaryOp op, SourceLocation loc);
// A STRING/WSTRING variable or string literal.
bool isStringValue(const TypeTable& t, const Value& v);

}  // namespace virtcom::st
