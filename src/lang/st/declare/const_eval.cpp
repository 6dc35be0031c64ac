#include "lang/st/declare/const_eval.hpp"

#include <cmath>

#include "lang/st/parse/lexer.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

int64_t constAsInt(const ConstValue& v) {
  if (v.kind == ConstValue::Kind::Real) return static_cast<int64_t>(std::llround(v.f));
  return v.i;
}

double constAsReal(const ConstValue& v) {
  if (v.kind == ConstValue::Kind::Real) return v.f;
  return static_cast<double>(v.i);
}

static ConstValue intValue(int64_t i) {
  ConstValue v;
  v.kind = ConstValue::Kind::Int;
  v.i = i;
  return v;
}

std::optional<ConstValue> characterConstant(const ConstValue& v, ElemType charType) {
  if (v.kind != ConstValue::Kind::String) return std::nullopt;
  int64_t code = 0;
  if (charType == ElemType::Wchar) {
    const std::u16string units = utf8ToUtf16(v.s);
    if (units.size() != 1) return std::nullopt;
    code = units[0];
  } else {
    if (v.s.size() != 1) return std::nullopt;
    code = static_cast<unsigned char>(v.s[0]);
  }
  ConstValue c = intValue(code);
  c.type = TypeTable::elem(charType);
  return c;
}

static ConstValue realValue(double f) {
  ConstValue v;
  v.kind = ConstValue::Kind::Real;
  v.f = f;
  return v;
}

static std::optional<ConstValue> foldReal(BinaryOp op, double x, double y) {
  switch (op) {
    case BinaryOp::Add: return realValue(x + y);
    case BinaryOp::Sub: return realValue(x - y);
    case BinaryOp::Mul: return realValue(x * y);
    case BinaryOp::Div: return realValue(x / y);
    case BinaryOp::Power: return realValue(std::pow(x, y));
    case BinaryOp::Lt: return intValue(x < y);
    case BinaryOp::Le: return intValue(x <= y);
    case BinaryOp::Gt: return intValue(x > y);
    case BinaryOp::Ge: return intValue(x >= y);
    case BinaryOp::Eq: return intValue(x == y);
    case BinaryOp::Ne: return intValue(x != y);
    default: return std::nullopt;
  }
}

static std::optional<ConstValue> foldInt(BinaryOp op, int64_t x, int64_t y) {
  auto ux = static_cast<uint64_t>(x), uy = static_cast<uint64_t>(y);
  switch (op) {
    case BinaryOp::Add: return intValue(static_cast<int64_t>(ux + uy));
    case BinaryOp::Sub: return intValue(static_cast<int64_t>(ux - uy));
    case BinaryOp::Mul: return intValue(static_cast<int64_t>(ux * uy));
    case BinaryOp::Div:
      if (y == 0) return std::nullopt;
      if (y == -1) return intValue(static_cast<int64_t>(0 - ux));
      return intValue(x / y);
    case BinaryOp::Mod:
      if (y == 0) return std::nullopt;
      if (y == -1) return intValue(0);
      return intValue(x % y);
    case BinaryOp::Power: return realValue(std::pow(static_cast<double>(x), static_cast<double>(y)));
    case BinaryOp::Lt: return intValue(x < y);
    case BinaryOp::Le: return intValue(x <= y);
    case BinaryOp::Gt: return intValue(x > y);
    case BinaryOp::Ge: return intValue(x >= y);
    case BinaryOp::Eq: return intValue(x == y);
    case BinaryOp::Ne: return intValue(x != y);
    case BinaryOp::And:
    case BinaryOp::AndThen: return intValue(static_cast<int64_t>(ux & uy));
    case BinaryOp::Or:
    case BinaryOp::OrElse: return intValue(static_cast<int64_t>(ux | uy));
    case BinaryOp::Xor: return intValue(static_cast<int64_t>(ux ^ uy));
  }
  return std::nullopt;
}

std::optional<ConstValue> foldBinary(BinaryOp op, const ConstValue& a, const ConstValue& b, bool real) {
  if (a.kind == ConstValue::Kind::String || b.kind == ConstValue::Kind::String) {
    if (op == BinaryOp::Eq) return intValue(a.s == b.s);
    if (op == BinaryOp::Ne) return intValue(a.s != b.s);
    return std::nullopt;
  }
  if (real) return foldReal(op, constAsReal(a), constAsReal(b));
  return foldInt(op, a.i, b.i);
}

std::optional<ConstValue> foldUnary(UnaryOp op, const ConstValue& a, bool real) {
  if (a.kind == ConstValue::Kind::String) return std::nullopt;
  switch (op) {
    case UnaryOp::Plus: return a;
    case UnaryOp::Neg:
      return real ? realValue(-constAsReal(a)) : intValue(static_cast<int64_t>(0 - static_cast<uint64_t>(a.i)));
    case UnaryOp::Not: return std::nullopt;  // width-dependent: folded by the caller
  }
  return std::nullopt;
}

std::optional<ConstValue> evalConst(const Expr& e, const ConstContext& ctx, Diagnostics& diags, bool quiet) {
  auto notConstant = [&]() -> std::optional<ConstValue> {
    if (!quiet) diags.error(diag::E101, e.loc, "expected a constant expression here");
    return std::nullopt;
  };
  switch (e.kind) {
    case ExprKind::IntLit:
    case ExprKind::BoolLit: {
      ConstValue v = intValue(static_cast<int64_t>(e.intValue));
      ElemType t;
      if (e.kind == ExprKind::BoolLit) v.type = TypeTable::elem(ElemType::Bool);
      if (!e.typePrefix.empty() && elemTypeByName(e.typePrefix, t)) v.type = TypeTable::elem(t);
      return v;
    }
    case ExprKind::TimeLit: {
      // Literals carry nanoseconds; TIME is stored in milliseconds, LTIME in nanoseconds.
      bool ltime = upper(e.typePrefix).starts_with("L");
      ConstValue v = intValue(ltime ? static_cast<int64_t>(e.intValue) : static_cast<int64_t>(e.intValue) / 1000000);
      v.type = TypeTable::elem(ltime ? ElemType::Ltime : ElemType::Time);
      return v;
    }
    case ExprKind::DateLit: {
      ConstValue v = intValue(static_cast<int64_t>(e.intValue));
      // The lexer names the type: DATE, TOD, DT, LDATE, LTOD, LDT.
      ElemType t = ElemType::Date;
      elemTypeByName(e.typePrefix, t);
      v.type = TypeTable::elem(t);
      return v;
    }
    case ExprKind::RealLit: {
      ConstValue v = realValue(e.realValue);
      ElemType t;
      if (!e.typePrefix.empty() && elemTypeByName(e.typePrefix, t)) v.type = TypeTable::elem(t);
      return v;
    }
    case ExprKind::StringLit: {
      ConstValue v;
      v.kind = ConstValue::Kind::String;
      v.s = e.text;
      ElemType t;
      if (e.typePrefix.empty() || !elemTypeByName(e.typePrefix, t) || elemTypeInfo(t).kind != ElemKind::Char) return v;
      if (auto c = characterConstant(v, t)) return c;  // CHAR#'a', WCHAR#"a"
      if (!quiet)
        diags.error(diag::E013, e.loc, e.typePrefix + "# needs a literal of exactly one character, as " +
                                           (t == ElemType::Wchar ? "WCHAR#\"a\"" : "CHAR#'a'"));
      return std::nullopt;
    }
    case ExprKind::EnumLit: {
      if (auto v = ctx.lookupEnum(e.typePrefix, e.text)) return v;
      if (!quiet) diags.error(diag::E102, e.loc, "'" + e.typePrefix + "#" + e.text + "' is not a known enumeration value");
      return std::nullopt;
    }
    case ExprKind::Name:
    case ExprKind::Member: {
      if (auto v = ctx.lookupName(e)) return v;
      return notConstant();
    }
    case ExprKind::Unary: {
      auto a = evalConst(*e.lhs, ctx, diags, quiet);
      if (!a) return std::nullopt;
      if (e.unaryOp == UnaryOp::Not) {
        // logical for BOOL, bitwise otherwise (the target's width truncates: NOT 16#00FF -> 16#FF00)
        if (a->type == TypeTable::elem(ElemType::Bool)) {
          ConstValue b = intValue(a->i == 0);
          b.type = a->type;
          return b;
        }
        ConstValue b = intValue(~a->i);
        b.type = a->type;
        return b;
      }
      return foldUnary(e.unaryOp, *a, a->kind == ConstValue::Kind::Real);
    }
    case ExprKind::Binary: {
      auto a = evalConst(*e.lhs, ctx, diags, quiet);
      if (!a) return std::nullopt;
      auto b = evalConst(*e.rhs, ctx, diags, quiet);
      if (!b) return std::nullopt;
      bool real = a->kind == ConstValue::Kind::Real || b->kind == ConstValue::Kind::Real;
      auto r = foldBinary(e.binaryOp, *a, *b, real);
      if (!r && !quiet) diags.error(diag::E103, e.loc, "constant expression cannot be evaluated (division by zero or invalid operands)");
      return r;
    }
    default: return notConstant();
  }
}

}  // namespace virtcom::st
