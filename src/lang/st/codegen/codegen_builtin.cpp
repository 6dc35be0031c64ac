// Code generation: the IEC standard functions (conversions, numeric, selection, bit shift,
// string functions, SCALE_X/NORM_X, ADR/REF/SIZEOF), checked and emitted inline or as CALLN.
#include <algorithm>
#include <map>

#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/declare/standard_names.hpp"

namespace virtcom::st {

using bc::Native;
using bc::Op;

namespace {

constexpr uint32_t kStringResultLength = 255;

TypeId elemId(ElemType e) { return TypeTable::elem(e); }

// IEC parameter names of the standard functions that take several inputs, in order; the others
// take IN (one input) or IN1, IN2, ... (extensible) and MUX takes K, IN0, IN1, ...
const std::map<std::string, std::vector<std::string>>& parameterNames() {
  static const std::map<std::string, std::vector<std::string>> kNames = {
      {"LIMIT", {"MN", "IN", "MX"}},       {"SEL", {"G", "IN0", "IN1"}},          {"SHL", {"IN", "N"}},
      {"SHR", {"IN", "N"}},                {"ROL", {"IN", "N"}},                  {"ROR", {"IN", "N"}},
      {"MID", {"IN", "L", "P"}},           {"LEFT", {"IN", "L"}},                 {"RIGHT", {"IN", "L"}},
      {"INSERT", {"IN1", "IN2", "P"}},     {"DELETE", {"IN", "L", "P"}},          {"REPLACE", {"IN1", "IN2", "L", "P"}},
      {"FIND", {"IN1", "IN2"}},            {"SCALE_X", {"MIN", "VALUE", "MAX"}},  {"NORM_X", {"MIN", "VALUE", "MAX"}},
      {"ATAN2", {"Y", "X"}},               {"EXPT", {"IN1", "IN2"}},              {"MOD", {"IN1", "IN2"}},
      {"SUB", {"IN1", "IN2"}},             {"DIV", {"IN1", "IN2"}}};
  return kNames;
}

// The index a named argument stands for, or -1.
int parameterIndex(const std::string& function, const std::string& upperName) {
  auto it = parameterNames().find(function);
  if (it != parameterNames().end()) {
    for (size_t i = 0; i < it->second.size(); ++i)
      if (it->second[i] == upperName) return static_cast<int>(i);
    return -1;
  }
  if (function == "MUX") {
    if (upperName == "K") return 0;
    if (upperName.size() > 2 && upperName.starts_with("IN")) return 1 + std::atoi(upperName.c_str() + 2);
    return -1;
  }
  if (upperName == "IN") return 0;
  if (upperName.size() > 2 && upperName.starts_with("IN")) return std::atoi(upperName.c_str() + 2) - 1;
  return -1;
}

std::optional<ElemType> typeFromName(const std::string& name) {
  ElemType e;
  if (name == "TIME_OF_DAY" || name == "TOD") return ElemType::Tod;
  if (name == "DATE_AND_TIME" || name == "DT") return ElemType::Dt;
  if (elemTypeByName(name, e)) return e;
  return std::nullopt;
}

// The native reading run-time text as a value of `to` where that is not a number's digits.
std::optional<bc::Native> textParser(const TypeTable& t, TypeId to) {
  if (t.isBool(to)) return bc::Native::STR_TO_BOOL;
  if (t.isElem(to, ElemType::Time)) return bc::Native::STR_TO_TIME;
  if (t.isElem(to, ElemType::Ltime)) return bc::Native::STR_TO_LTIME;
  if (t.isElem(to, ElemType::Date)) return bc::Native::STR_TO_DATE;
  if (t.isElem(to, ElemType::Tod)) return bc::Native::STR_TO_TOD;
  if (t.isElem(to, ElemType::Dt)) return bc::Native::STR_TO_DT;
  return std::nullopt;
}

}  // namespace

bc::Native wideNative(bc::Native narrow) {
  // natives.def lists the WSTR_* functions in the order of their STR_* twins
  int offset = static_cast<int>(bc::Native::WSTR_ASSIGN) - static_cast<int>(bc::Native::STR_ASSIGN);
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
  callNative(n, args, elemId(ElemType::Dint));
  Value v;
  v.kind = Value::Kind::Addr;
  v.type = stringType;
  v.place = tmp;
  return v;
}

static bool isStringValue(TypeTable& t, const Value& v) {
  return t.isString(v.type) || (v.kind == Value::Kind::Const && v.c.kind == ConstValue::Kind::String);
}

std::optional<Value> PouCompiler::builtin(const std::string& name, const Expr& e, TypeId expected) {
  if (auto op = codesysOperator(name, e)) return op;
  if (!isStandardFunctionName(name) && name != "__SYSTIME_NS") return std::nullopt;
  TypeTable& t = types();
  // The arguments in parameter order: positional as written, named ones by their IEC names.
  std::vector<const Expr*> ordered;
  for (const auto& a : e.args) {
    if (a.output) {
      diags().error(diag::E203, a.loc, name + " has no outputs");
      return Value::error();
    }
    size_t index = ordered.size();
    if (!a.name.empty()) {
      int i = parameterIndex(name, upper(a.name));
      if (i < 0 || i > 63) {
        diags().error(diag::E203, a.loc, name + " has no input '" + a.name + "'");
        return Value::error();
      }
      index = static_cast<size_t>(i);
    }
    if (ordered.size() <= index) ordered.resize(index + 1, nullptr);
    if (ordered[index]) {
      diags().error(diag::E203, a.loc, "input " + std::to_string(index + 1) + " of " + name + " is given twice");
      return Value::error();
    }
    ordered[index] = a.value.get();
  }
  for (size_t i = 0; i < ordered.size(); ++i)
    if (!ordered[i]) {
      diags().error(diag::E203, e.loc, name + " is missing input " + std::to_string(i + 1));
      return Value::error();
    }
  auto positional = [&](const Expr&, size_t i) { return ordered[i]; };
  auto argCount = [&](const Expr&) { return ordered.size(); };
  auto arity = [&](size_t lo, size_t hi) {
    if (argCount(e) < lo || argCount(e) > hi) {
      diags().error(diag::E203, e.loc, name + " takes " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + ".." + std::to_string(hi)) +
                                           " argument(s), found " + std::to_string(argCount(e)));
      return false;
    }
    return true;
  };
  auto arg = [&](size_t i, TypeId hint = kNoType) { return expr(*positional(e, i), hint); };
  auto toInt = [&](Value v, SourceLocation loc) { return toReg(coerce(v, elemId(ElemType::Dint), loc)); };
  bool wide = false;  // set by the first string argument: WSTRING functions are chosen then
  auto stringArg = [&](size_t i) -> std::optional<uint16_t> {
    Value v = arg(i);
    if (!v.ok()) return std::nullopt;
    if (!isStringValue(t, v)) {
      diags().error(diag::E202, positional(e, i)->loc, name + " needs a STRING here, found " + describe(t, v.type));
      return std::nullopt;
    }
    bool w = v.type != kNoType && t.isWideString(v.type);
    if (i == 0) wide = w;
    else if (w != wide) {
      diags().error(diag::E202, positional(e, i)->loc, name + " cannot mix STRING and WSTRING; convert with STRING_TO_WSTRING");
      return std::nullopt;
    }
    return toReg(v);
  };
  auto pick = [&](Native narrow) { return wide ? wideNative(narrow) : narrow; };
  auto realMath = [&](Native n) -> Value {
    if (!arity(1, 1)) return Value::error();
    Value v = arg(0, expected);
    if (!v.ok()) return v;
    if (!t.isNumeric(v.type)) {
      diags().error(diag::E202, e.loc, name + " needs a number, found " + describe(t, v.type));
      return Value::error();
    }
    TypeId rt = t.isReal(v.type) ? v.type : elemId(ElemType::Lreal);
    uint16_t x = toReg(convert(v, elemId(ElemType::Lreal), e.loc));
    return convert(callNative(n, {x}, elemId(ElemType::Lreal)), rt, e.loc);
  };

  // ---- conversions: X_TO_Y, TO_Y, TRUNC ----
  std::string src, dst;
  if (auto pos = name.find("_TO_"); pos != std::string::npos) {
    src = name.substr(0, pos);
    dst = name.substr(pos + 4);
  } else if (name.starts_with("TO_")) {
    dst = name.substr(3);
  }
  if (!dst.empty() && typeFromName(dst) && (src.empty() || typeFromName(src))) {
    if (!arity(1, 1)) return Value::error();
    Value v = arg(0);
    if (!v.ok()) return v;
    TypeId to = elemId(*typeFromName(dst));
    if (*typeFromName(dst) == ElemType::String) to = t.stringOf(kStringResultLength, false);
    if (!src.empty()) {
      TypeId from = elemId(*typeFromName(src));
      if (*typeFromName(src) == ElemType::String) {
        if (!isStringValue(t, v)) {
          diags().error(diag::E202, e.loc, name + " needs a STRING, found " + describe(t, v.type));
          return Value::error();
        }
      } else if (v.type != from && !(v.untyped)) {
        if (classifyConversion(t, v.type, from) == Conversion::Invalid && !(t.isEnum(v.type) && t.isInteger(from))) {
          diags().error(diag::E202, e.loc, name + " needs a " + src + ", found " + describe(t, v.type));
          return Value::error();
        }
      }
      if (v.untyped) v = convert(v, from, e.loc);
    }
    if (*typeFromName(dst) == ElemType::Wstring) to = t.stringOf(kStringResultLength, true);
    if (isStringValue(t, v)) {
      bool fromWide = v.type != kNoType && t.isWideString(v.type);
      if (t.isString(to) && fromWide == t.isWideString(to)) return v;
      if (t.isString(to))
        return stringResult(fromWide ? Native::STR_FROM_WSTR : Native::WSTR_FROM_STR, {toReg(v)}, to);
      uint16_t s = toReg(v);
      if (t.isReal(to)) return convert(callNative(Native::STR_TO_F, {s}, elemId(ElemType::Lreal)), to, e.loc);
      if (auto parse = textParser(t, to)) return callNative(*parse, {s}, to);
      return convert(callNative(Native::STR_TO_I, {s}, elemId(ElemType::Lint)), to, e.loc);
    }
    if (t.isString(to)) {
      uint16_t x = toReg(v);
      Native n = t.isBool(v.type) ? Native::STR_FROM_BOOL
                 : t.isElem(v.type, ElemType::Real) ? Native::STR_FROM_REAL
                 : t.isElem(v.type, ElemType::Lreal) ? Native::STR_FROM_LREAL
                 : t.isElem(v.type, ElemType::Time) ? Native::STR_FROM_TIME
                 : t.isElem(v.type, ElemType::Ltime) ? Native::STR_FROM_LTIME
                 : t.isElem(v.type, ElemType::Date) ? Native::STR_FROM_DATE
                 : t.isElem(v.type, ElemType::Tod) ? Native::STR_FROM_TOD
                 : t.isElem(v.type, ElemType::Dt) ? Native::STR_FROM_DT
                 : t.isSignedInt(v.type) ? Native::STR_FROM_I
                                         : Native::STR_FROM_U;
      return stringResult(n, {x}, to);
    }
    if (t.isEnum(v.type)) v.type = elemId(t.storageElem(v.type));
    if (t.isBool(v.type) && !t.isBool(to)) {
      Value b = v;
      b.type = elemId(ElemType::Usint);
      return convert(b, to, e.loc);
    }
    return convert(v, to, e.loc);
  }
  if (name == "TRUNC" || name == "TRUNC_INT") {
    if (!arity(1, 1)) return Value::error();
    Value v = arg(0);
    if (!v.ok()) return v;
    TypeId rt = elemId(name == "TRUNC" ? ElemType::Dint : ElemType::Int);
    if (!t.isReal(v.type)) return convert(v, rt, e.loc);
    uint16_t x = toReg(v), r = allocReg();
    emit(Op::F2I_TRUNC, r, x, 0);
    normalize(r, rt);
    return regValue(rt, r);
  }

  // ---- numeric ----
  static const std::map<std::string, Native> kMath = {
      {"SQRT", Native::SQRT}, {"LN", Native::LN},     {"LOG", Native::LOG},   {"EXP", Native::EXP},
      {"SIN", Native::SIN},   {"COS", Native::COS},   {"TAN", Native::TAN},   {"ASIN", Native::ASIN},
      {"ACOS", Native::ACOS}, {"ATAN", Native::ATAN}};
  if (auto m = kMath.find(name); m != kMath.end()) return realMath(m->second);
  if (name == "ATAN2" || name == "EXPT") {
    if (!arity(2, 2)) return Value::error();
    Value a = arg(0), b = arg(1);
    if (!a.ok() || !b.ok()) return Value::error();
    if (!t.isNumeric(a.type) || !t.isNumeric(b.type)) {
      diags().error(diag::E202, e.loc, name + " needs numbers");
      return Value::error();
    }
    TypeId rt = t.isElem(a.type, ElemType::Real) && (name == "EXPT" || t.isElem(b.type, ElemType::Real)) ? a.type : elemId(ElemType::Lreal);
    if (name == "EXPT" && t.isElem(a.type, ElemType::Real)) rt = a.type;
    uint16_t x = toReg(convert(a, elemId(ElemType::Lreal), e.loc));
    uint16_t y = toReg(convert(b, elemId(ElemType::Lreal), e.loc));
    return convert(callNative(name == "EXPT" ? Native::EXPT : Native::ATAN2, {x, y}, elemId(ElemType::Lreal)), rt, e.loc);
  }
  if (name == "ABS") {
    if (!arity(1, 1)) return Value::error();
    Value v = arg(0, expected);
    if (!v.ok()) return v;
    if (t.isReal(v.type)) return convert(callNative(Native::FABS, {toReg(v)}, v.type), v.type, e.loc);
    if (!t.isInteger(v.type) && !t.isTimeLike(v.type)) {
      diags().error(diag::E202, e.loc, "ABS needs a number, found " + describe(t, v.type));
      return Value::error();
    }
    uint16_t x = toReg(v), r = allocReg(), zero = loadConstInt(0), neg = allocReg();
    emit(Op::MOV, r, x, 0);
    if (t.isSignedInt(v.type) || t.isTimeLike(v.type)) {
      emit(Op::LT_I, neg, x, zero);
      uint32_t skip = emitJump(Op::JZ, neg);
      emit(Op::NEG, r, x, 0);
      normalize(r, v.type);
      patchJump(skip, here());
    }
    return regValue(v.type, r);
  }
  auto fakeBinary = [&](BinaryOp op) {
    Expr f;
    f.kind = ExprKind::Binary;
    f.binaryOp = op;
    f.loc = e.loc;
    return f;
  };
  static const std::map<std::string, BinaryOp> kArith = {{"ADD", BinaryOp::Add}, {"SUB", BinaryOp::Sub}, {"MUL", BinaryOp::Mul},
                                                         {"DIV", BinaryOp::Div}, {"MOD", BinaryOp::Mod}, {"AND", BinaryOp::And},
                                                         {"OR", BinaryOp::Or},   {"XOR", BinaryOp::Xor}};
  static const std::map<std::string, BinaryOp> kCompare = {{"GT", BinaryOp::Gt}, {"GE", BinaryOp::Ge}, {"EQ", BinaryOp::Eq},
                                                           {"LE", BinaryOp::Le}, {"LT", BinaryOp::Lt}, {"NE", BinaryOp::Ne}};
  if (auto op = kArith.find(name); op != kArith.end()) {
    bool variadic = name == "ADD" || name == "MUL" || name == "AND" || name == "OR" || name == "XOR";
    if (!arity(2, variadic ? 64 : 2)) return Value::error();
    Expr f = fakeBinary(op->second);
    Value acc = arg(0, expected);
    for (size_t i = 1; i < argCount(e) && acc.ok(); ++i) {
      Value next = arg(i, acc.untyped ? expected : acc.type);
      if (!next.ok()) return next;
      if (acc.untyped && !next.untyped) acc = coerce(acc, next.type, e.loc);
      acc = arithmetic(f, acc, next);
    }
    return acc;
  }
  if (auto op = kCompare.find(name); op != kCompare.end()) {
    if (!arity(2, 2)) return Value::error();
    Value a = arg(0), b = arg(1, kNoType);
    if (!a.ok() || !b.ok()) return Value::error();
    if (a.untyped && !b.untyped) a = coerce(a, b.type, e.loc);
    Expr f = fakeBinary(op->second);
    return compare(f, a, b);
  }
  if (name == "NOT") {
    if (!arity(1, 1)) return Value::error();
    Expr f;
    f.kind = ExprKind::Unary;
    f.unaryOp = UnaryOp::Not;
    f.loc = e.loc;
    Value v = arg(0, expected);
    if (!v.ok()) return v;
    uint16_t x = toReg(v), r = allocReg();
    if (t.isBool(v.type)) emit(Op::LNOT, r, x, 0);
    else if (t.isInteger(v.type)) {
      emit(Op::BNOT, r, x, 0);
      normalize(r, v.type);
    } else {
      diags().error(diag::E202, e.loc, "NOT needs a BOOL or bit string");
      return Value::error();
    }
    return regValue(v.type, r);
  }
  if (name == "MOVE") {
    if (!arity(1, 1)) return Value::error();
    return arg(0, expected);
  }
  if (name == "MIN" || name == "MAX" || name == "LIMIT") {
    bool limit = name == "LIMIT";
    if (!arity(limit ? 3 : 2, limit ? 3 : 64)) return Value::error();
    std::vector<Value> vals;
    TypeId common = kNoType;
    for (size_t i = 0; i < argCount(e); ++i) {
      Value v = arg(i, common != kNoType ? common : expected);
      if (!v.ok()) return v;
      vals.push_back(v);
    }
    for (auto& v : vals) {
      if (v.untyped) continue;
      if (common == kNoType) {
        common = v.type;
        continue;
      }
      Value a = regValue(common, 0), b = v;
      a.untyped = false;
      common = commonType(a, b);
      if (common == kNoType) {
        if (v.type == vals.front().type) common = v.type;
        else {
          diags().error(diag::E202, e.loc, name + " needs arguments of compatible types");
          return Value::error();
        }
      }
    }
    if (common == kNoType) common = vals.front().type;
    Expr lt = fakeBinary(BinaryOp::Lt);
    auto pick = [&](Value a, Value b, bool takeSmaller) {
      // r := a; if (b < a) == takeSmaller then r := b
      uint16_t ra = toReg(convert(coerce(a, common, e.loc), common, e.loc));
      uint16_t rb = toReg(convert(coerce(b, common, e.loc), common, e.loc));
      uint16_t r = allocReg();
      emit(Op::MOV, r, ra, 0);
      Value c = compare(lt, regValue(common, rb), regValue(common, ra));
      uint32_t skip = emitJump(takeSmaller ? Op::JZ : Op::JNZ, c.reg);
      emit(Op::MOV, r, rb, 0);
      patchJump(skip, here());
      return regValue(common, r);
    };
    if (limit) {
      // LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX)
      Value lo = pick(vals[1], vals[0], false);
      return pick(lo, vals[2], true);
    }
    Value acc = vals[0];
    for (size_t i = 1; i < vals.size(); ++i) acc = pick(acc, vals[i], name == "MIN");
    return acc;
  }
  if (name == "SEL" || name == "MUX") {
    bool sel = name == "SEL";
    if (!arity(sel ? 3 : 2, sel ? 3 : 64)) return Value::error();
    Value k = arg(0);
    if (!k.ok()) return k;
    if (sel && !t.isBool(k.type)) {
      diags().error(diag::E202, e.loc, "SEL needs a BOOL selector, found " + describe(t, k.type));
      return Value::error();
    }
    if (!sel && !t.isInteger(k.type)) {
      diags().error(diag::E202, e.loc, "MUX needs an integer selector, found " + describe(t, k.type));
      return Value::error();
    }
    uint16_t kr = toReg(k);
    std::vector<Value> ins;
    TypeId common = expected;
    for (size_t i = 1; i < argCount(e); ++i) {
      Value v = arg(i, common);
      if (!v.ok()) return v;
      if (!v.untyped && (common == kNoType || !t.isScalar(common))) common = v.type;
      ins.push_back(v);
    }
    if (common == kNoType) common = ins.front().type;
    bool strings = t.isString(common);
    if (strings) {
      // select the address of the chosen string; the result has the longest input's capacity
      for (const auto& v : ins)
        if (!t.isString(v.type)) {
          diags().error(diag::E202, e.loc, name + " inputs must all be strings or all elementary values");
          return Value::error();
        } else if (t[v.type].stringLength > t[common].stringLength) {
          common = v.type;
        }
    } else if (!t.isScalar(common)) {
      diags().error(diag::E108, e.loc, name + " supports elementary types and strings only");
      return Value::error();
    }
    // MUX with an out-of-range selector takes the last input (documented in docs/st-dialect.md).
    uint16_t r = allocReg();
    std::vector<uint32_t> done;
    for (size_t i = 0; i < ins.size(); ++i) {
      bool last = i + 1 == ins.size();
      uint32_t skip = 0;
      if (!last) {
        uint16_t c = allocReg(), idx = loadConstInt(static_cast<int64_t>(i));
        emit(Op::NE, c, kr, idx);
        skip = emitJump(Op::JNZ, c);
      }
      Value v = strings ? ins[i] : coerce(ins[i], common, e.loc);
      if (!v.ok()) return v;
      emit(Op::MOV, r, toReg(v), 0);
      if (!last) {
        done.push_back(emitJump(Op::JMP, 0));
        patchJump(skip, here());
      }
    }
    for (uint32_t d : done) patchJump(d, here());
    if (strings) {
      Value out;
      out.kind = Value::Kind::Addr;
      out.type = common;
      out.place.type = common;
      out.place.base = r;
      return out;
    }
    return regValue(common, r);
  }
  if (name == "SHL" || name == "SHR" || name == "ROL" || name == "ROR") {
    if (!arity(2, 2)) return Value::error();
    Value v = arg(0, expected);
    Value n = arg(1);
    if (!v.ok() || !n.ok()) return Value::error();
    if (v.untyped) v = convert(v, elemId(ElemType::Dword), e.loc);
    if (!t.isInteger(v.type)) {
      diags().error(diag::E202, e.loc, name + " needs a bit string or integer, found " + describe(t, v.type));
      return Value::error();
    }
    uint32_t bits = t.bits(v.type);
    uint16_t x = toReg(v), c = toInt(n, e.loc);
    if (name == "ROL" || name == "ROR") {
      uint16_t w = loadConstInt(bits);
      Value r = callNative(name == "ROL" ? Native::ROL : Native::ROR, {x, c, w}, v.type);
      normalize(r.reg, v.type);
      return r;
    }
    uint16_t r = allocReg();
    if (name == "SHR" && bits < 64) {
      emit(Op::ZEXT, r, x, static_cast<uint16_t>(bits));
      emit(Op::SHR, r, r, c);
    } else {
      emit(name == "SHL" ? Op::SHL : Op::SHR, r, x, c);
    }
    normalize(r, v.type);
    return regValue(v.type, r);
  }

  // ---- strings ----
  TypeId strResult = t.stringOf(kStringResultLength, false);
  TypeId wstrResult = t.stringOf(kStringResultLength, true);
  TypeId intT = elemId(ElemType::Int);
  if (name == "LEN") {
    if (!arity(1, 1)) return Value::error();
    auto s = stringArg(0);
    if (!s) return Value::error();
    return convert(callNative(pick(Native::STR_LEN), {*s}, elemId(ElemType::Dint)), intT, e.loc);
  }
  if (name == "LEFT" || name == "RIGHT") {
    if (!arity(2, 2)) return Value::error();
    auto s = stringArg(0);
    if (!s) return Value::error();
    uint16_t l = toInt(arg(1), e.loc);
    return stringResult(pick(name == "LEFT" ? Native::STR_LEFT : Native::STR_RIGHT), {*s, l}, (wide ? wstrResult : strResult));
  }
  if (name == "MID") {
    if (!arity(3, 3)) return Value::error();
    auto s = stringArg(0);
    if (!s) return Value::error();
    uint16_t l = toInt(arg(1), e.loc), p = toInt(arg(2), e.loc);
    return stringResult(pick(Native::STR_MID), {*s, l, p}, (wide ? wstrResult : strResult));
  }
  if (name == "CONCAT") {
    if (!arity(2, 64)) return Value::error();
    auto a = stringArg(0);
    if (!a) return Value::error();
    Value acc;
    uint16_t left = *a;
    for (size_t i = 1; i < argCount(e); ++i) {
      auto b = stringArg(i);
      if (!b) return Value::error();
      acc = stringResult(pick(Native::STR_CONCAT), {left, *b}, wide ? wstrResult : strResult);
      left = addressOf(acc.place);
    }
    return acc;
  }
  if (name == "INSERT") {
    if (!arity(3, 3)) return Value::error();
    auto a = stringArg(0), b = stringArg(1);
    if (!a || !b) return Value::error();
    uint16_t p = toInt(arg(2), e.loc);
    return stringResult(pick(Native::STR_INSERT), {*a, *b, p}, (wide ? wstrResult : strResult));
  }
  if (name == "DELETE") {
    if (!arity(3, 3)) return Value::error();
    auto s = stringArg(0);
    if (!s) return Value::error();
    uint16_t l = toInt(arg(1), e.loc), p = toInt(arg(2), e.loc);
    return stringResult(pick(Native::STR_DELETE), {*s, l, p}, (wide ? wstrResult : strResult));
  }
  if (name == "REPLACE") {
    if (!arity(4, 4)) return Value::error();
    auto a = stringArg(0), b = stringArg(1);
    if (!a || !b) return Value::error();
    uint16_t l = toInt(arg(2), e.loc), p = toInt(arg(3), e.loc);
    return stringResult(pick(Native::STR_REPLACE), {*a, *b, l, p}, (wide ? wstrResult : strResult));
  }
  if (name == "FIND") {
    if (!arity(2, 2)) return Value::error();
    auto a = stringArg(0), b = stringArg(1);
    if (!a || !b) return Value::error();
    return convert(callNative(pick(Native::STR_FIND), {*a, *b}, elemId(ElemType::Dint)), intT, e.loc);
  }

  // ---- scaling (TIA style: docs/st-dialect.md, SCALE_X NORM_X) ----
  if (name == "SCALE_X" || name == "NORM_X") {
    if (!arity(3, 3)) return Value::error();
    Value mn = arg(0), v = arg(1), mx = arg(2);
    if (!mn.ok() || !v.ok() || !mx.ok()) return Value::error();
    for (const Value* x : {&mn, &v, &mx})
      if (!t.isNumeric(x->type)) {
        diags().error(diag::E202, e.loc, name + " needs numbers");
        return Value::error();
      }
    auto typedLreal = [&](const Value& x) { return !x.untyped && t.isElem(x.type, ElemType::Lreal); };
    bool wide = typedLreal(mn) || typedLreal(v) || typedLreal(mx);
    TypeId rt = elemId(wide ? ElemType::Lreal : ElemType::Real);
    if (name == "SCALE_X" && expected != kNoType && t.isNumeric(expected)) rt = expected;
    TypeId lr = elemId(ElemType::Lreal);
    uint16_t a = toReg(convert(mn, lr, e.loc)), x = toReg(convert(v, lr, e.loc)), b = toReg(convert(mx, lr, e.loc));
    uint16_t span = allocReg(), r = allocReg();
    emit(Op::SUB_F, span, b, a);
    if (name == "SCALE_X") {
      emit(Op::MUL_F, r, x, span);
      emit(Op::ADD_F, r, r, a);
    } else {
      emit(Op::SUB_F, r, x, a);
      emit(Op::DIV_F, r, r, span);
    }
    return convert(regValue(lr, r), rt, e.loc);
  }

  // ---- addresses ----
  if (name == "ADR" || name == "REF") {
    if (!arity(1, 1)) return Value::error();
    auto p = place(*positional(e, 0), false);
    if (!p) return Value::error();
    if (p->bit >= 0 || p->valueBit >= 0) {
      diags().error(diag::E214, e.loc, "the address of a single bit cannot be taken");
      return Value::error();
    }
    uint16_t a = addressOf(*p);
    uint16_t r = allocReg();
    emit(Op::MOV, r, a, 0);
    return regValue(t.pointerTo(p->type), r);
  }
  if (name == "SIZEOF") {
    if (!arity(1, 1)) return Value::error();
    const Expr& x = *positional(e, 0);
    uint32_t size = 0;
    auto named = model().namedTypes.find(upper(x.text));
    ElemType et;
    if (x.kind == ExprKind::Name && !namePlace(x, false) && named != model().namedTypes.end()) size = t[named->second].size;
    else if (x.kind == ExprKind::Name && !namePlace(x, false) && elemTypeByName(x.text, et)) size = t[elemId(et)].size;
    else {
      auto p = place(x, false);
      if (!p) return Value::error();
      size = t[p->type].size;
    }
    return constInt(elemId(ElemType::Udint), size);
  }
  if (name == "__SYSTIME_NS") {
    uint16_t r = allocReg();
    emit(Op::SYSTIME, r, 0, 0);
    return regValue(elemId(ElemType::Ltime), r);
  }
  return std::nullopt;
}

}  // namespace virtcom::st
