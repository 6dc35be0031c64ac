// Code generation: the numeric and bit standard functions (ADD ... XOR, GT ... NE, NOT, MOVE,
// ABS, the math natives, SHL/SHR/ROL/ROR, SCALE_X/NORM_X).
#include "lang/st/codegen/builtin.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Op;

namespace {

TypeId elemId(ElemType e) { return TypeTable::elem(e); }

}  // namespace

// An untyped literal first input takes the type of the first typed one.
Value emitArithmetic(BuiltinCall& c) {
  Expr op = operatorExpr(c.fn.lowering.op, c.loc());
  Value acc = c.arg(0, c.expected);
  for (size_t i = 1; i < c.count() && acc.ok(); ++i) {
    Value next = c.arg(i, acc.untyped ? c.expected : acc.type);
    if (!next.ok()) return next;
    if (acc.untyped && !next.untyped) acc = c.pc.coerce(acc, next.type, c.loc());
    acc = c.pc.arithmetic(op, acc, next);
  }
  return acc;
}

Value emitComparison(BuiltinCall& c) {
  Value a = c.arg(0), b = c.arg(1, kNoType);
  if (!a.ok() || !b.ok()) return Value::error();
  if (a.untyped && !b.untyped) a = c.pc.coerce(a, b.type, c.loc());
  return c.pc.compare(operatorExpr(c.fn.lowering.op, c.loc()), a, b);
}

Value emitNegation(BuiltinCall& c) {
  TypeTable& t = c.types();
  Value v = c.arg(0, c.expected);
  if (!v.ok()) return v;
  uint16_t x = c.pc.toReg(v), r = c.pc.allocReg();
  if (t.isBool(v.type)) {
    c.pc.emit(Op::LNOT, r, x, 0);
  } else if (t.isInteger(v.type)) {
    c.pc.emit(Op::BNOT, r, x, 0);
    c.pc.normalize(r, v.type);
  } else {
    c.diags().error(diag::E202, c.loc(), "NOT needs a BOOL or bit string");
    return Value::error();
  }
  return c.pc.regValue(v.type, r);
}

Value emitMove(BuiltinCall& c) { return c.arg(0, c.expected); }

Value emitAbsolute(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  Value v = c.arg(0, c.expected);
  if (!v.ok()) return v;
  if (t.isReal(v.type)) return pc.convert(pc.callNative(bc::Native::FABS, {pc.toReg(v)}, v.type), v.type, c.loc());
  if (!t.isInteger(v.type) && !t.isTimeLike(v.type)) {
    c.diags().error(diag::E202, c.loc(), "ABS needs a number, found " + describe(t, v.type));
    return Value::error();
  }
  uint16_t x = pc.toReg(v), r = pc.allocReg(), zero = pc.loadConstInt(0), neg = pc.allocReg();
  pc.emit(Op::MOV, r, x, 0);
  if (t.isSignedInt(v.type) || t.isTimeLike(v.type)) {
    pc.emit(Op::LT_I, neg, x, zero);
    uint32_t skip = pc.emitJump(Op::JZ, neg);
    pc.emit(Op::NEG, r, x, 0);
    pc.normalize(r, v.type);
    pc.patchJump(skip, pc.here());
  }
  return pc.regValue(v.type, r);
}

// Computed in LREAL; the result is REAL for a REAL input, LREAL otherwise.
Value emitMathNative(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  Value v = c.arg(0, c.expected);
  if (!v.ok()) return v;
  if (!t.isNumeric(v.type)) {
    c.diags().error(diag::E202, c.loc(), c.name() + " needs a number, found " + describe(t, v.type));
    return Value::error();
  }
  TypeId rt = t.isReal(v.type) ? v.type : elemId(ElemType::Lreal);
  uint16_t x = pc.toReg(pc.convert(v, elemId(ElemType::Lreal), c.loc()));
  return pc.convert(pc.callNative(c.fn.lowering.native, {x}, elemId(ElemType::Lreal)), rt, c.loc());
}

// The result is REAL when the base is (EXPT) or both inputs are (ATAN2), LREAL otherwise.
Value emitMathNative2(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  Value a = c.arg(0), b = c.arg(1);
  if (!a.ok() || !b.ok()) return Value::error();
  if (!t.isNumeric(a.type) || !t.isNumeric(b.type)) {
    c.diags().error(diag::E202, c.loc(), c.name() + " needs numbers");
    return Value::error();
  }
  bool power = c.fn.id == StandardFunctionId::EXPT;
  bool real = t.isElem(a.type, ElemType::Real) && (power || t.isElem(b.type, ElemType::Real));
  TypeId rt = real ? a.type : elemId(ElemType::Lreal);
  uint16_t x = pc.toReg(pc.convert(a, elemId(ElemType::Lreal), c.loc()));
  uint16_t y = pc.toReg(pc.convert(b, elemId(ElemType::Lreal), c.loc()));
  return pc.convert(pc.callNative(c.fn.lowering.native, {x, y}, elemId(ElemType::Lreal)), rt, c.loc());
}

// Within the width of the input's type; an untyped literal input counts as DWORD.
Value emitBitShift(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  Value v = c.arg(0, c.expected);
  Value n = c.arg(1);
  if (!v.ok() || !n.ok()) return Value::error();
  if (v.untyped) v = pc.convert(v, elemId(ElemType::Dword), c.loc());
  if (!t.isInteger(v.type)) {
    c.diags().error(diag::E202, c.loc(), c.name() + " needs a bit string or integer, found " + describe(t, v.type));
    return Value::error();
  }
  uint32_t bits = t.bits(v.type);
  uint16_t x = pc.toReg(v), count = c.dint(n);
  if (c.fn.lowering.kind == Lowering::Kind::Native) {
    uint16_t width = pc.loadConstInt(bits);
    Value r = pc.callNative(c.fn.lowering.native, {x, count, width}, v.type);
    pc.normalize(r.reg, v.type);
    return r;
  }
  bool right = c.fn.id == StandardFunctionId::SHR;
  uint16_t r = pc.allocReg();
  if (right && bits < 64) {  // shift in zeros: drop the sign extension first
    pc.emit(Op::ZEXT, r, x, static_cast<uint16_t>(bits));
    pc.emit(Op::SHR, r, r, count);
  } else {
    pc.emit(right ? Op::SHR : Op::SHL, r, x, count);
  }
  pc.normalize(r, v.type);
  return pc.regValue(v.type, r);
}

// SCALE_X(MIN, VALUE, MAX) = VALUE * (MAX - MIN) + MIN, NORM_X = (VALUE - MIN) / (MAX - MIN),
// in LREAL; the result is LREAL if a typed input is, else REAL (SCALE_X: the expected type).
Value emitScaling(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  Value mn = c.arg(0), v = c.arg(1), mx = c.arg(2);
  if (!mn.ok() || !v.ok() || !mx.ok()) return Value::error();
  for (const Value* x : {&mn, &v, &mx})
    if (!t.isNumeric(x->type)) {
      c.diags().error(diag::E202, c.loc(), c.name() + " needs numbers");
      return Value::error();
    }
  auto typedLreal = [&](const Value& x) { return !x.untyped && t.isElem(x.type, ElemType::Lreal); };
  bool wide = typedLreal(mn) || typedLreal(v) || typedLreal(mx);
  bool scale = c.fn.id == StandardFunctionId::SCALE_X;
  TypeId rt = elemId(wide ? ElemType::Lreal : ElemType::Real);
  if (scale && c.expected != kNoType && t.isNumeric(c.expected)) rt = c.expected;
  TypeId lr = elemId(ElemType::Lreal);
  uint16_t a = pc.toReg(pc.convert(mn, lr, c.loc())), x = pc.toReg(pc.convert(v, lr, c.loc()));
  uint16_t b = pc.toReg(pc.convert(mx, lr, c.loc()));
  uint16_t span = pc.allocReg(), r = pc.allocReg();
  pc.emit(Op::SUB_F, span, b, a);
  if (scale) {
    pc.emit(Op::MUL_F, r, x, span);
    pc.emit(Op::ADD_F, r, r, a);
  } else {
    pc.emit(Op::SUB_F, r, x, a);
    pc.emit(Op::DIV_F, r, r, span);
  }
  return pc.convert(pc.regValue(lr, r), rt, c.loc());
}

}  // namespace virtcom::st
