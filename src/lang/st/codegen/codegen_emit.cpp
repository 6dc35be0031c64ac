// Code generation: instruction emission, registers, loads/stores, conversions and assignment.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "lang/st/codegen/check.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/lexer.hpp"

namespace virtcom::st {

using bc::Op;

bc::Op loadOp(ElemType e) {
  switch (e) {
    case ElemType::Bool: case ElemType::Byte: case ElemType::Usint: case ElemType::Char: return Op::LD_U8;
    case ElemType::Sint: return Op::LD_I8;
    case ElemType::Int: return Op::LD_I16;
    case ElemType::Word: case ElemType::Uint: case ElemType::Wchar: return Op::LD_U16;
    case ElemType::Dint: case ElemType::Time: return Op::LD_I32;
    case ElemType::Dword: case ElemType::Udint: case ElemType::Date: case ElemType::Tod: case ElemType::Dt: return Op::LD_U32;
    case ElemType::Real: return Op::LD_F32;
    default: return Op::LD_64;
  }
}

bc::Op loadAbsOp(ElemType e) {
  switch (loadOp(e)) {
    case Op::LD_U8: return Op::LDA_U8;
    case Op::LD_I8: return Op::LDA_I8;
    case Op::LD_I16: return Op::LDA_I16;
    case Op::LD_U16: return Op::LDA_U16;
    case Op::LD_I32: return Op::LDA_I32;
    case Op::LD_U32: return Op::LDA_U32;
    case Op::LD_F32: return Op::LDA_F32;
    default: return Op::LDA_64;
  }
}

bc::Op storeOp(ElemType e) {
  if (e == ElemType::Real) return Op::ST_F32;
  switch (elemTypeInfo(e).sizeBytes) {
    case 1: return Op::ST_8;
    case 2: return Op::ST_16;
    case 4: return Op::ST_32;
    default: return Op::ST_64;
  }
}

bc::Op storeAbsOp(ElemType e) {
  switch (storeOp(e)) {
    case Op::ST_8: return Op::STA_8;
    case Op::ST_16: return Op::STA_16;
    case Op::ST_32: return Op::STA_32;
    case Op::ST_F32: return Op::STA_F32;
    default: return Op::STA_64;
  }
}

std::string describe(const TypeTable& types, TypeId t) { return t == kNoType ? "?" : types.name(t); }

PouCompiler::PouCompiler(CompileContext& ctx, PouSym& pou) : ctx_(ctx), pou_(pou) {}

uint16_t PouCompiler::allocReg() {
  uint16_t r = nextReg_++;
  regTop_ = std::max(regTop_, nextReg_);
  if (nextReg_ > maxReg_) maxReg_ = nextReg_;
  if (nextReg_ >= 0xfff0) {
    diags().error(diag::E108, pou_.ast->loc, "expression too complex (out of registers)");
    nextReg_ = 2;
  }
  return r;
}

uint32_t PouCompiler::emit(Op op, uint16_t a, uint16_t b, uint16_t c) {
  ctx_.module.code.push_back(bc::Instr::abc(op, a, b, c));
  return static_cast<uint32_t>(ctx_.module.code.size() - 1);
}

uint32_t PouCompiler::emitBx(Op op, uint16_t a, uint32_t bx) {
  ctx_.module.code.push_back(bc::Instr::abx(op, a, bx));
  return static_cast<uint32_t>(ctx_.module.code.size() - 1);
}

uint32_t PouCompiler::here() const { return static_cast<uint32_t>(ctx_.module.code.size()); }

void PouCompiler::patchJump(uint32_t at, uint32_t target) {
  bc::Instr& in = ctx_.module.code[at];
  in = bc::Instr::asbx(in.op, in.a, static_cast<int32_t>(target) - static_cast<int32_t>(at + 1));
}

uint32_t PouCompiler::emitJump(Op op, uint16_t reg) { return emitBx(op, reg, 0); }

void PouCompiler::jumpTo(Op op, uint16_t reg, uint32_t target) { patchJump(emitJump(op, reg), target); }

uint16_t PouCompiler::loadConstInt(int64_t v, uint16_t into) {
  uint16_t r = into == 0xffff ? allocReg() : into;
  if (v >= INT32_MIN && v <= INT32_MAX) {
    emitBx(Op::LDI, r, static_cast<uint32_t>(static_cast<int32_t>(v)));
  } else {
    ctx_.module.constants.push_back(static_cast<uint64_t>(v));
    emitBx(Op::LDK, r, static_cast<uint32_t>(ctx_.module.constants.size() - 1));
  }
  return r;
}

uint16_t PouCompiler::indexDesc(const bc::IndexDesc& d) {
  auto& all = ctx_.module.indexes;
  auto same = [&d](const bc::IndexDesc& x) { return x.lo == d.lo && x.count == d.count && x.stride == d.stride; };
  auto it = std::find_if(all.begin(), all.end(), same);
  if (it != all.end()) return static_cast<uint16_t>(it - all.begin());
  if (all.size() > 0xffff) {
    diags().error(diag::E108, pou_.ast->loc, "too many distinct array shapes (more than 65536)");
    return 0;
  }
  all.push_back(d);
  return static_cast<uint16_t>(all.size() - 1);
}

uint16_t PouCompiler::loadConstReal(double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, 8);
  ctx_.module.constants.push_back(bits);
  uint16_t r = allocReg();
  emitBx(Op::LDK, r, static_cast<uint32_t>(ctx_.module.constants.size() - 1));
  return r;
}

Place PouCompiler::frameTemp(TypeId type) {
  uint32_t align = std::min<uint32_t>(std::max<uint32_t>(types()[type].align, 1), 8);
  uint32_t offset = (pou_.frameSize + tempTop_ + align - 1) / align * align;
  tempTop_ = offset + types()[type].size - pou_.frameSize;
  tempMax_ = std::max(tempMax_, tempTop_);
  Place p;
  p.type = type;
  p.base = kFp;
  p.offset = offset;
  return p;
}

uint32_t PouCompiler::stringLiteral(const std::string& bytes, bool wide) {
  std::string withNul;
  if (wide) {
    for (char16_t unit : utf8ToUtf16(bytes)) {  // UTF-16LE
      withNul.push_back(static_cast<char>(unit & 0xFF));
      withNul.push_back(static_cast<char>(unit >> 8));
    }
    withNul.push_back('\0');
  } else {
    withNul = bytes;
  }
  withNul.push_back('\0');
  return ctx_.image.addData(withNul.data(), static_cast<uint32_t>(withNul.size()));
}

Value PouCompiler::regValue(TypeId type, uint16_t reg) {
  Value v;
  v.kind = Value::Kind::Reg;
  v.type = type;
  v.reg = reg;
  return v;
}

std::optional<int16_t> PouCompiler::smallConst(const Value& v) {
  if (v.kind != Value::Kind::Const || v.c.kind != ConstValue::Kind::Int) return std::nullopt;
  if (v.c.i < INT16_MIN || v.c.i > INT16_MAX) return std::nullopt;
  return static_cast<int16_t>(v.c.i);
}

Value PouCompiler::constInt(TypeId type, int64_t i) {
  Value v;
  v.kind = Value::Kind::Const;
  v.type = type;
  v.c.kind = ConstValue::Kind::Int;
  v.c.i = i;
  return v;
}

uint16_t PouCompiler::addressOf(const Place& p) {
  if (p.base == kAbsolute) return loadConstInt(p.offset);
  if (p.offset == 0) return p.base;
  uint16_t r = allocReg();
  if (p.offset <= 0x7fff) {
    emit(Op::ADDI, r, p.base, static_cast<uint16_t>(p.offset));
  } else {
    loadConstInt(p.offset, r);
    emit(Op::ADD, r, p.base, r);
  }
  return r;
}

// Brings a register-relative place's offset into the 16-bit C field.
static Place reachable(PouCompiler& pc, const Place& p) {
  if (p.base == kAbsolute || p.offset <= 0xffff) return p;
  Place q = p;
  q.base = pc.addressOf(p);
  q.offset = 0;
  return q;
}

uint16_t PouCompiler::load(const Place& p) {
  uint16_t r = allocReg();
  if (p.valueBit >= 0) {
    Place host = p;
    host.type = p.bitHost;
    host.valueBit = -1;
    uint16_t w = load(host);
    uint16_t k = loadConstInt(p.valueBit);
    emit(Op::SHR, r, w, k);
    loadConstInt(1, k);
    emit(Op::BAND, r, r, k);
    return r;
  }
  if (p.bit >= 0) {
    uint16_t a = addressOf(p);
    emit(Op::LD_BIT, r, a, static_cast<uint16_t>(p.bit));
    return r;
  }
  ElemType e = types().storageElem(p.type);
  if (p.base == kAbsolute) {
    emitBx(loadAbsOp(e), r, p.offset);
  } else {
    Place q = reachable(*this, p);
    emit(loadOp(e), r, q.base, static_cast<uint16_t>(q.offset));
  }
  return r;
}

void PouCompiler::store(const Place& p, uint16_t reg) {
  if (p.valueBit >= 0) {
    // read-modify-write of one bit of an integer
    Place host = p;
    host.type = p.bitHost;
    host.valueBit = -1;
    uint16_t w = load(host);
    uint16_t mask = loadConstInt(int64_t(1) << p.valueBit);
    uint16_t inv = allocReg();
    emit(Op::BNOT, inv, mask, 0);
    emit(Op::BAND, w, w, inv);
    uint16_t bit = allocReg();
    emit(Op::LNOT, bit, reg, 0);
    emit(Op::LNOT, bit, bit, 0);
    uint16_t k = loadConstInt(p.valueBit);
    emit(Op::SHL, bit, bit, k);
    emit(Op::BOR, w, w, bit);
    store(host, w);
    return;
  }
  if (p.bit >= 0) {
    uint16_t a = addressOf(p);
    emit(Op::ST_BIT, reg, a, static_cast<uint16_t>(p.bit));
    return;
  }
  ElemType e = types().storageElem(p.type);
  if (p.base == kAbsolute) {
    emitBx(storeAbsOp(e), reg, p.offset);
  } else {
    Place q = reachable(*this, p);
    emit(storeOp(e), reg, q.base, static_cast<uint16_t>(q.offset));
  }
}

void PouCompiler::copyBytes(uint16_t dst, uint16_t src, uint32_t size) {
  uint16_t n = loadConstInt(size);
  emit(Op::COPY, dst, src, n);
}

// Integers narrower than 64 bits (BOOL is always 0 or 1) live sign- or zero-extended.
static bool hasExtension(const TypeTable& t, TypeId type) {
  if (!t.isScalar(type) || t.isReal(type)) return false;
  ElemType e = t.storageElem(type);
  return bitWidth(e) < 64 && e != ElemType::Bool;
}

namespace {

struct TimeScaling {
  int64_t unitsPerDay = 0;  // non-zero: split the day (in the source's unit) first
  bool keepClock = false;   // ... and keep the time of day (else the midnight)
  int64_t multiply = 1;
  int64_t divide = 1;
};

// A duration or date converts as the point in time it stands for: a duration counts from 0,
// DATE/DT/LDATE/LDT from 1970-01-01-00:00, TOD/LTOD from midnight. The number changes its
// unit (DT seconds to TOD milliseconds: * 1000, LTIME to TIME: / 1e6, toward zero); a target
// without a clock (DATE, LDATE) keeps the midnight of the day, a clock (TOD, LTOD) the time
// within the day, both by floor (a negative LTIME or a LDT before 1970 falls on the day before).
// So TIME_TO_DT(T#1d2h) is DT#1970-01-02-02:00:00, DT_TO_TIME gives the milliseconds since
// 1970 (wrapping in TIME's 32 bits as CODESYS does), TOD_TO_DT is the clock on 1970-01-01 and
// DATE_TO_TOD the midnight.
TimeScaling timeScaling(ElemType from, ElemType to) {
  const int64_t fu = timeUnitNs(from), tu = timeUnitNs(to);
  const DatePart fp = datePart(from), tp = datePart(to);
  TimeScaling s;
  if (from == to || fu == 0 || tu == 0) return s;
  if ((tp == DatePart::Day || tp == DatePart::Clock) && fp != tp) {
    s.unitsPerDay = 86'400'000'000'000 / fu;
    s.keepClock = tp == DatePart::Clock;
  }
  if (fu > tu) s.multiply = fu / tu;
  if (tu > fu) s.divide = tu / fu;
  return s;
}

// x mod d rounded toward minus infinity (the time within the day also before 1970).
int64_t floorMod(int64_t x, int64_t d) { return ((x % d) + d) % d; }

}  // namespace

uint16_t PouCompiler::normalize(uint16_t reg, TypeId type) { return normalizeInto(reg, reg, type); }

uint16_t PouCompiler::normalizedCopy(uint16_t reg, TypeId type) {
  if (!hasExtension(types(), type)) return reg;
  return normalizeInto(allocReg(), reg, type);
}

uint16_t PouCompiler::normalizeInto(uint16_t to, uint16_t reg, TypeId type) {
  if (!hasExtension(types(), type)) return reg;
  ElemType e = types().storageElem(type);
  uint32_t bits = bitWidth(e);
  bool isSigned = isSignedInt(e) || e == ElemType::Time;
  emit(isSigned ? Op::SEXT : Op::ZEXT, to, reg, static_cast<uint16_t>(bits));
  return to;
}

uint16_t PouCompiler::rawReg(const Value& v) { return v.kind == Value::Kind::Reg ? v.reg : toReg(v); }

Value PouCompiler::wrappedValue(TypeId type, uint16_t reg) {
  Value v = regValue(type, reg);
  v.wrapped = hasExtension(types(), type);
  return v;
}

uint16_t PouCompiler::toReg(Value v) {
  switch (v.kind) {
    // Into a new register: the wrapped register keeps what its instruction computed, so load
    // forwarding can serve a repeated `a[j - 1]` from both (an in-place SEXT hides it).
    case Value::Kind::Reg: return v.wrapped ? normalizedCopy(v.reg, v.type) : v.reg;
    case Value::Kind::Const:
      if (v.type != kNoType && types().isReal(v.type)) return loadConstReal(constAsReal(v.c));
      if (v.c.kind == ConstValue::Kind::Real) return loadConstReal(v.c.f);
      if (v.c.kind == ConstValue::Kind::String) {
        bool wide = v.type != kNoType && types().isWideString(v.type);
        return loadConstInt(stringLiteral(v.c.s, wide));
      }
      return loadConstInt(v.c.i);
    case Value::Kind::Addr: {
      if (types().isScalar(v.place.type)) return load(v.place);
      return addressOf(v.place);
    }
    default: return allocReg();
  }
}

static bool fitsInteger(const TypeTable& types, TypeId t, int64_t v) {
  ElemType e = types.storageElem(t);
  uint32_t bits = bitWidth(e);
  if (bits >= 64) return true;
  if (isSignedInt(e) || e == ElemType::Time) return v >= -(int64_t(1) << (bits - 1)) && v < (int64_t(1) << (bits - 1));
  return v >= 0 && v < (int64_t(1) << bits);
}

Value PouCompiler::convert(Value v, TypeId to, SourceLocation loc) {
  if (!v.ok() || to == kNoType) return Value::error();
  TypeId from = v.type;
  TypeTable& t = types();
  if (from == to) return v;
  // Constants convert at compile time.
  if (v.kind == Value::Kind::Const && t.isScalar(to) && v.c.kind != ConstValue::Kind::String) {
    Value c = v;
    c.type = to;
    c.untyped = false;
    if (t.isReal(to)) {
      c.c.f = constAsReal(v.c);
      if (t.isElem(to, ElemType::Real)) c.c.f = static_cast<double>(static_cast<float>(c.c.f));
      c.c.kind = ConstValue::Kind::Real;
      return c;
    }
    if (t.isBool(to)) {
      c.c.i = constAsInt(v.c) != 0;
      c.c.kind = ConstValue::Kind::Int;
      return c;
    }
    int64_t i = v.c.kind == ConstValue::Kind::Real ? static_cast<int64_t>(std::llround(v.c.f)) : v.c.i;
    // The same steps as the code emitted below at run time.
    if (from != kNoType) {
      const TimeScaling s = timeScaling(t.storageElem(from), t.storageElem(to));
      if (s.unitsPerDay) {
        const int64_t rem = floorMod(i, s.unitsPerDay);
        i = s.keepClock ? rem : i - rem;
      }
      if (s.multiply > 1) i *= s.multiply;
      if (s.divide > 1) i /= s.divide;
    }
    // wrap to the target width
    ElemType e = t.storageElem(to);
    uint32_t bits = bitWidth(e);
    if (bits < 64 && e != ElemType::Bool) {
      uint64_t mask = (uint64_t(1) << bits) - 1;
      uint64_t u = static_cast<uint64_t>(i) & mask;
      bool sign = isSignedInt(e) || e == ElemType::Time;
      if (sign && (u >> (bits - 1)) & 1) u |= ~mask;
      i = static_cast<int64_t>(u);
    }
    c.c.i = i;
    c.c.kind = ConstValue::Kind::Int;
    return c;
  }
  if (t.isString(to) || t.isString(from) || !t.isScalar(to) || !t.isScalar(from)) {
    if (t.isString(to) && t.isString(from)) {
      Value out = v;
      out.type = to;
      return out;
    }
    if (!t.isScalar(to) && !t.isScalar(from) && t[from].size == t[to].size) {
      Value out = v;
      out.type = to;
      return out;
    }
    diags().error(diag::E202, loc, "cannot convert " + describe(t, from) + " to " + describe(t, to));
    return Value::error();
  }
  uint16_t r = toReg(v);
  uint16_t out = allocReg();
  bool fromReal = t.isReal(from), toReal = t.isReal(to);
  ElemType fe = t.storageElem(from), te = t.storageElem(to);
  if (t.isBool(to) && !t.isBool(from)) {
    uint16_t z = loadConstInt(0);
    emit(fromReal ? Op::NE_F : Op::NE, out, r, z);
    return regValue(to, out);
  }
  if (fromReal && toReal) {
    emit(te == ElemType::Real ? Op::RND_F32 : Op::MOV, out, r, 0);
    return regValue(to, out);
  }
  if (!fromReal && toReal) {
    // TIME and the 64-bit durations and dates are signed; DATE, TOD, DT unsigned 32-bit.
    bool signedTime = timeUnitNs(fe) != 0 && (fe == ElemType::Time || elemTypeInfo(fe).sizeBytes == 8);
    bool unsignedSrc = !(isSignedInt(fe) || signedTime);
    emit(unsignedSrc ? Op::U2F : Op::I2F, out, r, 0);
    if (te == ElemType::Real) emit(Op::RND_F32, out, out, 0);
    return regValue(to, out);
  }
  if (fromReal && !toReal) {
    emit(Op::F2I, out, r, 0);
    normalize(out, to);
    return regValue(to, out);
  }
  // integer-like to integer-like; durations and dates change their unit (timeScaling)
  const TimeScaling s = timeScaling(fe, te);
  if (s.unitsPerDay) {
    // floorMod: (r % d + d) % d
    uint16_t rem = allocReg(), day = loadConstInt(s.unitsPerDay);
    emit(Op::MOD_I, rem, r, day);
    emit(Op::ADD, rem, rem, day);
    emit(Op::MOD_I, rem, rem, day);
    if (s.keepClock) {
      r = rem;
    } else {
      uint16_t midnight = allocReg();
      emit(Op::SUB, midnight, r, rem);
      r = midnight;
    }
  }
  if (s.multiply > 1) {
    emit(Op::MUL, out, r, loadConstInt(s.multiply));
  } else if (s.divide > 1) {
    emit(Op::DIV_I, out, r, loadConstInt(s.divide));
  } else {
    emit(Op::MOV, out, r, 0);
  }
  normalize(out, to);
  return regValue(to, out);
}

Value PouCompiler::coerce(Value v, TypeId to, SourceLocation loc) {
  if (!v.ok() || to == kNoType) return Value::error();
  TypeTable& t = types();
  if (v.type == to) return v;
  if (v.untyped && v.kind == Value::Kind::Const) {
    // Literals adapt to their target if the value fits.
    if (t.isInteger(to) || t.isEnum(to)) {
      if (v.c.kind == ConstValue::Kind::Real) {
        diags().error(diag::E202, loc, "a REAL literal cannot be assigned to " + describe(t, to));
        return Value::error();
      }
      if (!fitsInteger(t, to, v.c.i)) {
        diags().error(diag::E117, loc, "literal " + std::to_string(v.c.i) + " is out of range for " + describe(t, to));
        return Value::error();
      }
      if (t.isEnum(to)) {
        diags().error(diag::E202, loc, "an integer cannot be assigned to enumeration " + describe(t, to));
        return Value::error();
      }
      return convert(v, to, loc);
    }
    if (t.isReal(to)) return convert(v, to, loc);
    if (t.isBool(to) && v.c.kind == ConstValue::Kind::Int && (v.c.i == 0 || v.c.i == 1)) return convert(v, to, loc);
  }
  if (t.isChar(to) && v.kind == Value::Kind::Const && v.c.kind == ConstValue::Kind::String) {
    if (auto ch = characterConstant(v.c, t[to].elem)) {
      Value out = v;
      out.c = *ch;
      out.type = to;
      return out;
    }
    diags().error(diag::E202, loc, "a " + describe(t, to) + " takes a literal of exactly one character (" +
                                       (t[to].elem == ElemType::Wchar ? "\"a\"" : "'a'") + "), found a string of " +
                                       std::to_string(v.c.s.size()) + " bytes");
    return Value::error();
  }
  if (v.type == kNoType) {
    diags().error(diag::E202, loc, "expression has no value");
    return Value::error();
  }
  if (t.isEnum(v.type) && t.isInteger(to)) {
    // CODESYS converts an enumeration to its integer value implicitly (not the other way round).
    Value base = v;
    base.type = TypeTable::elem(t.storageElem(v.type));
    return coerce(base, to, loc);
  }
  if (t.isEnum(v.type) || t.isEnum(to)) {
    diags().error(diag::E202, loc, "type mismatch: cannot assign " + describe(t, v.type) + " to " + describe(t, to));
    return Value::error();
  }
  if (t.isPointer(to) && (t.isInteger(v.type) && t.bits(v.type) >= 32)) {
    // CODESYS lets integers (0, addresses computed as LWORD) be assigned to pointers
    Value out = v;
    out.type = to;
    return out.kind == Value::Kind::Const ? out : convert(regValue(TypeTable::elem(ElemType::Lword), toReg(v)), to, loc);
  }
  if (t.isInteger(to) && t.bits(to) >= 32 && t.isPointer(v.type)) {
    Value out = regValue(TypeTable::elem(ElemType::Lword), toReg(v));
    return convert(out, to, loc);
  }
  if (t.isPointer(to) && t.isPointer(v.type) && v.untypedAddress) {
    // CODESYS: ADR gives an untyped address, which any POINTER TO takes.
    Value out = v;
    out.type = to;
    return out;
  }
  if ((t.isPointer(to) || t.isReference(to)) && (t.isPointer(v.type) || t.isReference(v.type))) {
    TypeId a = t[to].element, b = t[v.type].element;
    // ADR(buffer) for a POINTER TO its element type, as CODESYS code walks arrays (`p[i]`).
    while (b != kNoType && t[b].kind == bc::TypeKind::Array && a != b) b = t[b].element;
    if (a == kNoType || b == kNoType || t.isElem(a, ElemType::Byte) || sameOrDerivedFb(model(), b, a)) {
      Value out = v;
      out.type = to;
      return out;
    }
  }
  switch (classifyConversion(t, v.type, to)) {
    case Conversion::Same:
      if (t.isScalar(to)) return convert(v, to, loc);
      {
        Value out = v;
        out.type = to;
        return out;
      }
    case Conversion::Widening: return convert(v, to, loc);
    case Conversion::Narrowing:
      diags().warning(diag::W301, loc, "implicit conversion from " + describe(t, v.type) + " to " + describe(t, to) +
                                           " may lose data; use an explicit conversion such as " + describe(t, v.type) +
                                           "_TO_" + describe(t, to));
      return convert(v, to, loc);
    case Conversion::Invalid: break;
  }
  diags().error(diag::E202, loc, "type mismatch: cannot assign " + describe(t, v.type) + " to " + describe(t, to));
  return Value::error();
}

void PouCompiler::assignValue(const Place& target, Value v, SourceLocation loc) {
  TypeTable& t = types();
  TypeId tt = target.type;
  if (tt == kNoType) return;
  if (t.isString(tt)) {
    if (!v.ok()) return;
    bool srcIsString = t.isString(v.type) || (v.kind == Value::Kind::Const && v.c.kind == ConstValue::Kind::String);
    if (!srcIsString || (v.type != kNoType && t.isWideString(v.type) != t.isWideString(tt))) {
      diags().error(diag::E202, loc, "type mismatch: cannot assign " + describe(t, v.type) + " to " + describe(t, tt));
      return;
    }
    uint16_t dst = addressOf(target);
    uint16_t cap = loadConstInt(t[tt].stringLength);
    uint16_t src = toReg(v);
    bc::Native n = t.isWideString(tt) ? wideNative(bc::Native::STR_ASSIGN) : bc::Native::STR_ASSIGN;
    (void)callNative(n, {dst, cap, src}, TypeTable::elem(ElemType::Dint));
    return;
  }
  if (auto itf = model().interfaceByType.find(tt); itf != model().interfaceByType.end()) {
    // An interface variable holds the address of an instance whose class implements it.
    if (!v.ok()) return;
    std::string name = upper(itf->second->name);
    auto from = model().interfaceByType.find(v.type);
    // `itf := 0` resets the interface; an interface converts to any interface it extends.
    bool isNull = v.kind == Value::Kind::Const && t.isInteger(v.type) && v.c.i == 0;
    if (isNull || (from != model().interfaceByType.end() && interfaceExtends(model(), upper(from->second->name), name))) {
      store(target, toReg(v));
      return;
    }
    auto fb = model().fbByType.find(v.type);
    if (fb == model().fbByType.end() || v.kind != Value::Kind::Addr || !implementsInterface(model(), fb->second, name)) {
      diags().error(diag::E202, loc, describe(t, v.type) + " does not implement " + itf->second->name);
      return;
    }
    store(target, addressOf(v.place));
    return;
  }
  if (!t.isScalar(tt)) {
    if (!v.ok()) return;
    if (!sameType(t, v.type, tt)) {
      diags().error(diag::E202, loc, "type mismatch: cannot assign " + describe(t, v.type) + " to " + describe(t, tt));
      return;
    }
    uint16_t dst = addressOf(target);
    uint16_t src = toReg(v);
    copyBytes(dst, src, t[tt].size);
    return;
  }
  Value c = coerce(v, tt, loc);
  if (!c.ok()) return;
  if (storeConst(target, c)) return;
  store(target, rawReg(c));  // a store keeps only the low bits of its width
}

bool PouCompiler::storeConst(const Place& p, const Value& v) {
  std::optional<int16_t> k = smallConst(v);
  if (!k || p.base == kAbsolute || p.bit >= 0 || p.valueBit >= 0 || p.offset > 0xffff || types().isReal(p.type))
    return false;
  Op op = Op::STK_64;
  switch (storeOp(types().storageElem(p.type))) {
    case Op::ST_8: op = Op::STK_8; break;
    case Op::ST_16: op = Op::STK_16; break;
    case Op::ST_32: op = Op::STK_32; break;
    default: break;
  }
  emit(op, static_cast<uint16_t>(*k), p.base, static_cast<uint16_t>(p.offset));
  return true;
}

void PouCompiler::assign(const Place& target, const Expr& source, SourceLocation loc) {
  Value v = expr(source, target.type);
  assignValue(target, v, loc);
}

}  // namespace virtcom::st
