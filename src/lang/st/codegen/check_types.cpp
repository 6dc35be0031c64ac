// Relations between types: the common type of two operands, FB and interface inheritance
// (EXTENDS, IMPLEMENTS) for the checks and for dynamic dispatch.
#include <algorithm>

#include "lang/st/codegen/check.hpp"

namespace virtcom::st {

namespace {

// The depth limit guards against EXTENDS cycles, which the declarer reports but keeps.
bool extendsWithin(const ProgramModel& m, const std::string& itf, const std::string& target, int depth) {
  if (itf == target) return true;
  if (depth > 16) return false;
  auto it = m.interfaces.find(itf);
  if (it == m.interfaces.end()) return false;
  for (const auto& b : it->second.bases)
    if (extendsWithin(m, b, target, depth + 1)) return true;
  return false;
}

// Integer widths by rank: 1 = 8 bits ... 4 = 64 bits.
int intRank(ElemType e) {
  switch (e) {
    case ElemType::Sint: case ElemType::Usint: case ElemType::Byte: return 1;
    case ElemType::Int: case ElemType::Uint: case ElemType::Word: return 2;
    case ElemType::Dint: case ElemType::Udint: case ElemType::Dword: return 3;
    default: return 4;
  }
}

ElemType signedOfRank(int r) {
  switch (r) {
    case 1: return ElemType::Sint;
    case 2: return ElemType::Int;
    case 3: return ElemType::Dint;
    default: return ElemType::Lint;
  }
}

}  // namespace

bool derivesFrom(const PouSym* c, const PouSym* base) {
  for (; c; c = c->base)
    if (c == base) return true;
  return false;
}

bool sameOrDerivedFb(const ProgramModel& m, TypeId actual, TypeId wanted) {
  if (actual == wanted) return true;
  auto a = m.fbByType.find(actual), w = m.fbByType.find(wanted);
  return a != m.fbByType.end() && w != m.fbByType.end() && derivesFrom(a->second, w->second);
}

bool interfaceExtends(const ProgramModel& m, const std::string& itf, const std::string& target) {
  return extendsWithin(m, itf, target, 0);
}

bool implementsInterface(const ProgramModel& m, const PouSym* c, const std::string& itf) {
  for (; c; c = c->base)
    for (const auto& i : c->interfaces)
      if (interfaceExtends(m, i, itf)) return true;
  return false;
}

TypeId commonType(const TypeTable& t, const Value& a, const Value& b) {
  auto realLiteral = [&](const Value& v) { return v.untyped && v.c.kind == ConstValue::Kind::Real; };
  if (realLiteral(b) && t.isInteger(a.type)) return TypeTable::elem(ElemType::Real);
  if (realLiteral(a) && t.isInteger(b.type)) return TypeTable::elem(ElemType::Real);
  if (a.untyped && !b.untyped) return b.type;
  if (b.untyped && !a.untyped) return a.type;
  if (a.type == b.type) return a.type;
  if (t.isReal(a.type) || t.isReal(b.type)) {
    if (t.isElem(a.type, ElemType::Lreal) || t.isElem(b.type, ElemType::Lreal)) return TypeTable::elem(ElemType::Lreal);
    if (t.isNumeric(a.type) && t.isNumeric(b.type)) return TypeTable::elem(ElemType::Real);
    return kNoType;
  }
  if (t.isInteger(a.type) && t.isInteger(b.type)) {
    ElemType ea = t.storageElem(a.type), eb = t.storageElem(b.type);
    int ra = intRank(ea), rb = intRank(eb);
    bool sa = isSignedInt(ea), sb = isSignedInt(eb);
    if (sa == sb) return ra >= rb ? a.type : b.type;
    int su = sa ? ra : rb, uu = sa ? rb : ra;
    return TypeTable::elem(signedOfRank(std::max(su, std::min(uu + 1, 4))));
  }
  if (t.isBool(a.type) && t.isBitString(b.type)) return b.type;
  if (t.isBool(b.type) && t.isBitString(a.type)) return a.type;
  if (t.isTimeLike(a.type) && t.isTimeLike(b.type)) return TypeTable::elem(ElemType::Ltime);
  return kNoType;
}

}  // namespace virtcom::st
