// Code generation: the conversions <FROM>_TO_<TO> and TO_<TO> (numbers inline, text by the
// STR_ natives) and TRUNC/TRUNC_INT.
#include "lang/st/codegen/builtin.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Native;
using bc::Op;

namespace {

TypeId elemId(ElemType e) { return TypeTable::elem(e); }

// The native reading run-time text as a value of `to` where that is not a number's digits.
std::optional<Native> textParser(const TypeTable& t, TypeId to) {
  if (t.isBool(to)) return Native::STR_TO_BOOL;
  if (t.isElem(to, ElemType::Time)) return Native::STR_TO_TIME;
  if (t.isElem(to, ElemType::Ltime)) return Native::STR_TO_LTIME;
  if (t.isElem(to, ElemType::Date)) return Native::STR_TO_DATE;
  if (t.isElem(to, ElemType::Tod)) return Native::STR_TO_TOD;
  if (t.isElem(to, ElemType::Dt)) return Native::STR_TO_DT;
  if (t.isElem(to, ElemType::Ldate)) return Native::STR_TO_LDATE;
  if (t.isElem(to, ElemType::Ltod)) return Native::STR_TO_LTOD;
  if (t.isElem(to, ElemType::Ldt)) return Native::STR_TO_LDT;
  return std::nullopt;
}

// The native writing a value of `from` as text (IEC literal text for times and dates).
Native textWriter(const TypeTable& t, TypeId from) {
  if (t.isBool(from)) return Native::STR_FROM_BOOL;
  if (t.isElem(from, ElemType::Real)) return Native::STR_FROM_REAL;
  if (t.isElem(from, ElemType::Lreal)) return Native::STR_FROM_LREAL;
  if (t.isElem(from, ElemType::Time)) return Native::STR_FROM_TIME;
  if (t.isElem(from, ElemType::Ltime)) return Native::STR_FROM_LTIME;
  if (t.isElem(from, ElemType::Date)) return Native::STR_FROM_DATE;
  if (t.isElem(from, ElemType::Tod)) return Native::STR_FROM_TOD;
  if (t.isElem(from, ElemType::Dt)) return Native::STR_FROM_DT;
  if (t.isElem(from, ElemType::Ldate)) return Native::STR_FROM_LDATE;
  if (t.isElem(from, ElemType::Ltod)) return Native::STR_FROM_LTOD;
  if (t.isElem(from, ElemType::Ldt)) return Native::STR_FROM_LDT;
  return t.isSignedInt(from) ? Native::STR_FROM_I : Native::STR_FROM_U;
}

// <FROM>_TO_<TO> takes a FROM (an untyped literal becomes one; an enumeration passes for an
// integer); false after E202.
bool checkSource(BuiltinCall& c, Value& v) {
  TypeTable& t = c.types();
  const ConversionTypes& conv = c.fn.conversion;
  TypeId from = elemId(*conv.from);
  std::string wanted(conv.fromName);
  if (*conv.from == ElemType::String) {
    if (!isStringValue(t, v)) {
      c.diags().error(diag::E202, c.loc(), c.name() + " needs a STRING, found " + describe(t, v.type));
      return false;
    }
  } else if (v.type != from && !v.untyped) {
    if (classifyConversion(t, v.type, from) == Conversion::Invalid && !(t.isEnum(v.type) && t.isInteger(from))) {
      c.diags().error(diag::E202, c.loc(), c.name() + " needs a " + wanted + ", found " + describe(t, v.type));
      return false;
    }
  }
  if (v.untyped) v = c.pc.convert(v, from, c.loc());
  return true;
}

// Text in: the same text, the other width, or the value the text spells.
Value fromText(BuiltinCall& c, const Value& v, TypeId to) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  bool fromWide = v.type != kNoType && t.isWideString(v.type);
  if (t.isString(to) && fromWide == t.isWideString(to)) return v;
  if (t.isString(to)) return pc.stringResult(fromWide ? Native::STR_FROM_WSTR : Native::WSTR_FROM_STR, {pc.toReg(v)}, to);
  uint16_t s = pc.toReg(v);
  if (t.isChar(to)) {  // the first character (STRING_TO_CHAR, WSTRING_TO_WCHAR, STRING_TO_WCHAR, ...)
    const TypeId unit = elemId(fromWide ? ElemType::Wchar : ElemType::Char);
    return pc.convert(pc.callNative(fromWide ? Native::WSTR_TO_WCHAR : Native::STR_TO_CHAR, {s}, unit), to, c.loc());
  }
  if (t.isReal(to)) return pc.convert(pc.callNative(Native::STR_TO_F, {s}, elemId(ElemType::Lreal)), to, c.loc());
  if (auto parse = textParser(t, to)) return pc.callNative(*parse, {s}, to);
  return pc.convert(pc.callNative(Native::STR_TO_I, {s}, elemId(ElemType::Lint)), to, c.loc());
}

}  // namespace

Value emitConversion(BuiltinCall& c) {
  TypeTable& t = c.types();
  PouCompiler& pc = c.pc;
  const ConversionTypes& conv = c.fn.conversion;
  // CHAR_TO_BYTE('a'): a literal where a character is expected is one (as in an assignment)
  Value v = c.arg(0, conv.from && elemTypeInfo(*conv.from).kind == ElemKind::Char ? elemId(*conv.from) : kNoType);
  if (!v.ok()) return v;
  // STRING(255) is registered before the source check and WSTRING(255) after it: the order
  // the module's type table has always had.
  TypeId to = conv.to == ElemType::String ? t.stringOf(kStringResultLength, false) : elemId(conv.to);
  if (conv.from && !checkSource(c, v)) return Value::error();
  if (conv.to == ElemType::Wstring) to = t.stringOf(kStringResultLength, true);
  if (isStringValue(t, v)) return fromText(c, v, to);
  if (t.isChar(v.type) && t.isString(to)) {  // a text of the one character, then its width
    const bool wide = t.isElem(v.type, ElemType::Wchar);
    uint16_t x = pc.toReg(v);
    Value one = pc.stringResult(wide ? Native::WSTR_FROM_WCHAR : Native::STR_FROM_CHAR, {x}, t.stringOf(1, wide));
    return fromText(c, one, to);
  }
  if (t.isString(to)) {
    uint16_t x = pc.toReg(v);
    return pc.stringResult(textWriter(t, v.type), {x}, to);
  }
  if (t.isEnum(v.type)) v.type = elemId(t.storageElem(v.type));
  if (t.isBool(v.type) && !t.isBool(to)) {  // FALSE/TRUE as the numbers 0/1
    Value b = v;
    b.type = elemId(ElemType::Usint);
    return pc.convert(b, to, c.loc());
  }
  return pc.convert(v, to, c.loc());
}

// Toward zero; TRUNC gives DINT (CODESYS), TRUNC_INT INT.
Value emitTruncation(BuiltinCall& c) {
  PouCompiler& pc = c.pc;
  Value v = c.arg(0);
  if (!v.ok()) return v;
  TypeId rt = elemId(c.fn.id == StandardFunctionId::TRUNC ? ElemType::Dint : ElemType::Int);
  if (!c.types().isReal(v.type)) return pc.convert(v, rt, c.loc());
  uint16_t x = pc.toReg(v), r = pc.allocReg();
  pc.emit(Op::F2I_TRUNC, r, x, 0);
  pc.normalize(r, rt);
  return pc.regValue(rt, r);
}

}  // namespace virtcom::st
