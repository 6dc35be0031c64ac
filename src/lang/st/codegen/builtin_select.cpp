// Code generation: the selection standard functions MIN, MAX, LIMIT, SEL and MUX, lowered to
// compares, moves and jumps.
#include "lang/st/codegen/builtin.hpp"
#include "lang/st/codegen/check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Op;

namespace {

// The common type of the typed inputs (literals adapt to it); nullopt with E202 if two are
// incompatible. All inputs untyped: the first one's type.
std::optional<TypeId> extremumType(BuiltinCall& c, const std::vector<Value>& values) {
  TypeId common = kNoType;
  for (const Value& v : values) {
    if (v.untyped) continue;
    if (common == kNoType) {
      common = v.type;
      continue;
    }
    Value a = c.pc.regValue(common, 0), b = v;
    a.untyped = false;
    common = commonType(c.types(), a, b);
    if (common == kNoType) {
      if (v.type != values.front().type) {
        c.diags().error(diag::E202, c.loc(), c.name() + " needs arguments of compatible types");
        return std::nullopt;
      }
      common = v.type;
    }
  }
  return common == kNoType ? values.front().type : common;
}

// r := a; IF (b < a) = takeSmaller THEN r := b
Value pickOne(BuiltinCall& c, TypeId common, Value a, Value b, bool takeSmaller) {
  PouCompiler& pc = c.pc;
  uint16_t ra = pc.toReg(pc.convert(pc.coerce(a, common, c.loc()), common, c.loc()));
  uint16_t rb = pc.toReg(pc.convert(pc.coerce(b, common, c.loc()), common, c.loc()));
  uint16_t r = pc.allocReg();
  pc.emit(Op::MOV, r, ra, 0);
  Value less = pc.compare(operatorExpr(BinaryOp::Lt, c.loc()), pc.regValue(common, rb), pc.regValue(common, ra));
  uint32_t skip = pc.emitJump(takeSmaller ? Op::JZ : Op::JNZ, less.reg);
  pc.emit(Op::MOV, r, rb, 0);
  pc.patchJump(skip, pc.here());
  return pc.regValue(common, r);
}

// The type the inputs are selected in; strings select by address and take the longest input's
// capacity. kNoType after E202/E108 for inputs that cannot be selected together.
TypeId selectionType(BuiltinCall& c, const std::vector<Value>& inputs, TypeId common) {
  TypeTable& t = c.types();
  if (common == kNoType) common = inputs.front().type;
  if (t.isString(common)) {
    for (const Value& v : inputs)
      if (!t.isString(v.type)) {
        c.diags().error(diag::E202, c.loc(), c.name() + " inputs must all be strings or all elementary values");
        return kNoType;
      } else if (t[v.type].stringLength > t[common].stringLength) {
        common = v.type;
      }
  } else if (!t.isScalar(common)) {
    c.diags().error(diag::E108, c.loc(), c.name() + " supports elementary types and strings only");
    return kNoType;
  }
  return common;
}

// The selector: SEL's BOOL G or MUX's integer K (`isSigned` set for a signed K); nullopt after E202.
std::optional<uint16_t> selector(BuiltinCall& c, bool sel, bool& isSigned) {
  TypeTable& t = c.types();
  Value k = c.arg(0);
  if (!k.ok()) return std::nullopt;
  if (sel && !t.isBool(k.type)) {
    c.diags().error(diag::E202, c.loc(), "SEL needs a BOOL selector, found " + describe(t, k.type));
    return std::nullopt;
  }
  if (!sel && !t.isInteger(k.type)) {
    c.diags().error(diag::E202, c.loc(), "MUX needs an integer selector, found " + describe(t, k.type));
    return std::nullopt;
  }
  isSigned = t.isSignedInt(k.type);
  return c.pc.toReg(k);
}

}  // namespace

// MIN/MAX fold over the inputs; LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX).
Value emitExtremum(BuiltinCall& c) {
  std::vector<Value> values;
  for (size_t i = 0; i < c.count(); ++i) {
    Value v = c.arg(i, c.expected);
    if (!v.ok()) return v;
    values.push_back(v);
  }
  std::optional<TypeId> found = extremumType(c, values);
  if (!found) return Value::error();
  TypeId common = *found;
  if (c.fn.id == StandardFunctionId::LIMIT) {
    Value lo = pickOne(c, common, values[1], values[0], false);
    return pickOne(c, common, lo, values[2], true);
  }
  Value acc = values[0];
  for (size_t i = 1; i < values.size(); ++i) acc = pickOne(c, common, acc, values[i], c.fn.id == StandardFunctionId::MIN);
  return acc;
}

// SEL(G, IN0, IN1) and MUX(K, IN0, ...): a chain of compare-and-jump over the inputs. MUX
// clamps an out-of-range selector: a negative K takes the first input, a K past the end the
// last (documented in docs/st-dialect.md).
Value emitSelection(BuiltinCall& c) {
  PouCompiler& pc = c.pc;
  bool signedSelector = false;
  auto kr = selector(c, c.fn.id == StandardFunctionId::SEL, signedSelector);
  if (!kr) return Value::error();
  std::vector<Value> inputs;
  TypeId common = c.expected;
  for (size_t i = 1; i < c.count(); ++i) {
    Value v = c.arg(i, common);
    if (!v.ok()) return v;
    if (!v.untyped && (common == kNoType || !c.types().isScalar(common))) common = v.type;
    inputs.push_back(v);
  }
  common = selectionType(c, inputs, common);
  if (common == kNoType) return Value::error();
  bool strings = c.types().isString(common);
  uint16_t r = pc.allocReg();
  std::vector<uint32_t> done;
  for (size_t i = 0; i < inputs.size(); ++i) {
    bool last = i + 1 == inputs.size();
    uint32_t skip = 0;
    if (!last) {
      uint16_t differs = pc.allocReg();
      if (i == 0 && signedSelector) {
        pc.emit(Op::GTK, differs, *kr, 0);  // K <= 0 takes IN0
      } else {
        pc.emit(Op::NE, differs, *kr, pc.loadConstInt(static_cast<int64_t>(i)));
      }
      skip = pc.emitJump(Op::JNZ, differs);
    }
    Value v = strings ? inputs[i] : pc.coerce(inputs[i], common, c.loc());
    if (!v.ok()) return v;
    pc.emit(Op::MOV, r, pc.toReg(v), 0);
    if (!last) {
      done.push_back(pc.emitJump(Op::JMP, 0));
      pc.patchJump(skip, pc.here());
    }
  }
  for (uint32_t d : done) pc.patchJump(d, pc.here());
  if (!strings) return pc.regValue(common, r);
  Value out;
  out.kind = Value::Kind::Addr;
  out.type = common;
  out.place.type = common;
  out.place.base = r;
  return out;
}

}  // namespace virtcom::st
