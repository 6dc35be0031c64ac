// Code generation: calls of the IEC standard functions (declare/standard_functions.def). The
// call's arguments are bound and counted here, then the function's family emits it
// (builtin_*.cpp); ADR, REF, SIZEOF and the engine's clock intrinsic live here too.
#include <algorithm>

#include "lang/st/codegen/builtin.hpp"
#include "lang/st/codegen/check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Native;
using bc::Op;

namespace {

using Emitter = Value (*)(BuiltinCall&);

constexpr Emitter kEmitters[] = {
#define FAMILY(Name, what) &emit##Name,
#include "lang/st/declare/standard_functions.def"
};
static_assert(std::size(kEmitters) == static_cast<size_t>(StandardFamily::Count_));

// The task clock in ns as LTIME, for the standard FBs written in ST (prelude.cpp) and SFC
// lowering. Not an IEC name, so not reserved; it takes no inputs (any given are ignored).
constexpr std::string_view kClockIntrinsic = "__SYSTIME_NS";

// These families have always registered STRING(255) and WSTRING(255) before their arguments
// are counted, whether they return a string or not; kept so the module's type table (and the
// ids of types registered later) stay as they are.
bool registersStringResults(StandardFamily f) {
  switch (f) {
    case StandardFamily::StringQuery: case StandardFamily::StringEdit: case StandardFamily::StringConcat:
    case StandardFamily::Scaling: case StandardFamily::Address: case StandardFamily::SizeOf:
      return true;
    default:
      return false;
  }
}

void registerStringResults(TypeTable& t) {
  t.stringOf(kStringResultLength, false);
  t.stringOf(kStringResultLength, true);
}

}  // namespace

Expr operatorExpr(BinaryOp op, SourceLocation loc) {
  Expr f;
  f.kind = ExprKind::Binary;
  f.binaryOp = op;
  f.loc = loc;
  return f;
}

bool isStringValue(const TypeTable& t, const Value& v) {
  return t.isString(v.type) || (v.kind == Value::Kind::Const && v.c.kind == ConstValue::Kind::String);
}

bc::Native wideNative(bc::Native narrow) {
  // natives.def lists the WSTR_* functions in the order of their STR_* twins
  int offset = static_cast<int>(Native::WSTR_ASSIGN) - static_cast<int>(Native::STR_ASSIGN);
  switch (narrow) {
    case Native::STR_ASSIGN: case Native::STR_LEN: case Native::STR_CMP: case Native::STR_LEFT:
    case Native::STR_RIGHT: case Native::STR_MID: case Native::STR_CONCAT: case Native::STR_INSERT:
    case Native::STR_DELETE: case Native::STR_REPLACE: case Native::STR_FIND:
      return static_cast<Native>(static_cast<int>(narrow) + offset);
    default: return narrow;
  }
}

Value PouCompiler::callNative(Native n, const std::vector<uint16_t>& args, TypeId resultType) {
  // Arguments must sit in consecutive registers: copy them into a fresh block.
  uint16_t first = allocReg();
  for (size_t i = 1; i < std::max<size_t>(args.size(), 1); ++i) allocReg();
  for (size_t i = 0; i < args.size(); ++i) emit(Op::MOV, static_cast<uint16_t>(first + i), args[i], 0);
  emitBx(Op::CALLN, first, static_cast<uint32_t>(n));
  return regValue(resultType, first);
}

Value PouCompiler::stringResult(Native n, std::vector<uint16_t> args, TypeId stringType) {
  Place tmp = frameTemp(stringType);
  uint16_t dst = addressOf(tmp);
  uint16_t cap = loadConstInt(types()[stringType].stringLength);
  args.insert(args.begin(), {dst, cap});
  callNative(n, args, TypeTable::elem(ElemType::Dint));
  Value v;
  v.kind = Value::Kind::Addr;
  v.type = stringType;
  v.place = tmp;
  return v;
}

std::optional<Value> PouCompiler::builtin(const std::string& name, const Expr& e, TypeId expected) {
  if (auto op = codesysOperator(name, e)) return op;
  // TIME() (CODESYS/TwinCAT: the time since the PLC started, as OSCAT's T_PLC_MS reads it) and
  // LTIME(): the task clock, as every timer reads it, so virtual time.
  const bool clockOperator = (name == "TIME" || name == "LTIME") && e.args.empty();
  if (name == kClockIntrinsic || clockOperator) {
    if (!orderStandardArguments(diags(), name, ParameterNaming::Numbered, "", e)) return Value::error();
    registerStringResults(types());
    uint16_t r = allocReg();
    emit(Op::SYSTIME, r, 0, 0);
    const Value now = regValue(TypeTable::elem(ElemType::Ltime), r);
    return name == "TIME" ? convert(now, TypeTable::elem(ElemType::Time), e.loc) : now;
  }
  std::optional<StandardFunction> fn = findStandardFunction(name);
  if (!fn) return std::nullopt;
  auto args = orderStandardArguments(diags(), name, fn->naming, fn->parameters, e);
  if (!args) return Value::error();
  if (registersStringResults(fn->family)) registerStringResults(types());
  if (!checkArgumentCount(diags(), *fn, e.loc, args->size())) return Value::error();
  BuiltinCall call{*this, *fn, e, *args, expected};
  return kEmitters[static_cast<size_t>(fn->family)](call);
}

Value emitAddress(BuiltinCall& c) {
  PouCompiler& pc = c.pc;
  auto p = pc.place(*c.args[0], false);
  if (!p) return Value::error();
  if (p->bit >= 0 || p->valueBit >= 0) {
    c.diags().error(diag::E214, c.loc(), "the address of a single bit cannot be taken");
    return Value::error();
  }
  uint16_t a = pc.addressOf(*p);
  uint16_t r = pc.allocReg();
  pc.emit(Op::MOV, r, a, 0);
  Value v = pc.regValue(c.types().pointerTo(p->type), r);
  v.untypedAddress = c.fn.id == StandardFunctionId::ADR;  // REF stays typed (IEC)
  return v;
}

// SIZEOF(T) of a type name (unless a variable has that name) or SIZEOF(x) of a variable.
Value emitSizeOf(BuiltinCall& c) {
  PouCompiler& pc = c.pc;
  TypeTable& t = c.types();
  const Expr& x = *c.args[0];
  uint32_t size = 0;
  auto named = pc.model().namedTypes.find(upper(x.text));
  ElemType et;
  if (x.kind == ExprKind::Name && !pc.namePlace(x, false) && named != pc.model().namedTypes.end()) {
    size = t[named->second].size;
  } else if (x.kind == ExprKind::Name && !pc.namePlace(x, false) && elemTypeByName(x.text, et)) {
    size = t[TypeTable::elem(et)].size;
  } else {
    auto p = pc.place(x, false);
    if (!p) return Value::error();
    size = t[p->type].size;
  }
  return pc.constInt(TypeTable::elem(ElemType::Udint), size);
}

}  // namespace virtcom::st
