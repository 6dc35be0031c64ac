#include "lang/st/declare/type_table.hpp"

namespace virtcom::st {

TypeTable::TypeTable(std::vector<bc::TypeDesc>& storage) : types_(storage) {
  if (!types_.empty()) return;
#define X(e, nm, sz, category)                                                \
  {                                                                          \
    bc::TypeDesc d;                                                          \
    d.kind = ElemKind::category == ElemKind::Text ? bc::TypeKind::String : bc::TypeKind::Elementary; \
    d.name = nm;                                                             \
    d.elem = ElemType::e;                                                    \
    d.size = sz;                                                             \
    d.align = sz == 0 ? 1 : sz;                                              \
    types_.push_back(std::move(d));                                          \
  }
#include "core/elementary_types.def"
#undef X
  // The default-length strings take the STRING / WSTRING slots.
  for (ElemType e : {ElemType::String, ElemType::Wstring}) {
    bc::TypeDesc& d = types_[elem(e)];
    bool wide = e == ElemType::Wstring;
    d.stringLength = 80;
    d.size = wide ? 2 * 81 : 81;
    d.align = wide ? 2 : 1;
    strings_[{80, wide}] = elem(e);
  }
}

TypeId TypeTable::stringOf(uint32_t length, bool wide) {
  auto it = strings_.find({length, wide});
  if (it != strings_.end()) return it->second;
  bc::TypeDesc d;
  d.kind = bc::TypeKind::String;
  d.elem = wide ? ElemType::Wstring : ElemType::String;
  d.name = std::string(wide ? "WSTRING(" : "STRING(") + std::to_string(length) + ")";
  d.stringLength = length;
  d.size = (length + 1) * (wide ? 2 : 1);
  d.align = wide ? 2 : 1;
  types_.push_back(std::move(d));
  TypeId id = static_cast<TypeId>(types_.size() - 1);
  strings_[{length, wide}] = id;
  return id;
}

TypeId TypeTable::arrayOf(TypeId element, const std::vector<bc::ArrayDim>& dims) {
  std::string name = "ARRAY [";
  uint64_t count = 1;
  for (size_t i = 0; i < dims.size(); ++i) {
    if (i) name += ", ";
    name += std::to_string(dims[i].lo) + ".." + std::to_string(dims[i].hi);
    count *= dims[i].count();
  }
  name += "] OF " + types_[element].name;
  auto it = interned_.find(name);
  if (it != interned_.end()) return it->second;
  bc::TypeDesc d;
  d.kind = bc::TypeKind::Array;
  d.name = name;
  d.element = element;
  d.dims = dims;
  d.align = types_[element].align;
  d.size = static_cast<uint32_t>(count * types_[element].size);
  types_.push_back(std::move(d));
  TypeId id = static_cast<TypeId>(types_.size() - 1);
  interned_[name] = id;
  return id;
}

static TypeId internIndirect(std::vector<bc::TypeDesc>& types, std::map<std::string, TypeId>& interned,
                             bc::TypeKind kind, const char* prefix, TypeId target) {
  std::string name = std::string(prefix) + (target == kNoType ? "BYTE" : types[target].name);
  auto it = interned.find(name);
  if (it != interned.end()) return it->second;
  bc::TypeDesc d;
  d.kind = kind;
  d.name = name;
  d.element = target;
  d.elem = ElemType::Lword;
  d.size = 8;
  d.align = 8;
  types.push_back(std::move(d));
  TypeId id = static_cast<TypeId>(types.size() - 1);
  interned[name] = id;
  return id;
}

TypeId TypeTable::pointerTo(TypeId target) {
  return internIndirect(types_, interned_, bc::TypeKind::Pointer, "POINTER TO ", target);
}

TypeId TypeTable::referenceTo(TypeId target) {
  return internIndirect(types_, interned_, bc::TypeKind::Reference, "REFERENCE TO ", target);
}

TypeId TypeTable::addNamed(bc::TypeKind kind, std::string name) {
  bc::TypeDesc d;
  d.kind = kind;
  d.name = std::move(name);
  d.elem = ElemType::Int;  // enums default to INT
  types_.push_back(std::move(d));
  return static_cast<TypeId>(types_.size() - 1);
}

bool TypeTable::isInteger(TypeId t) const {
  return isElementary(t) && isIntegerKind(elemTypeInfo(types_[t].elem).kind);
}
bool TypeTable::isBitString(TypeId t) const {
  if (!isElementary(t)) return false;
  ElemKind k = elemTypeInfo(types_[t].elem).kind;
  return k == ElemKind::Bits || k == ElemKind::Bool;
}
bool TypeTable::isSignedInt(TypeId t) const {
  return isElementary(t) && elemTypeInfo(types_[t].elem).kind == ElemKind::Signed;
}
bool TypeTable::isReal(TypeId t) const {
  return isElementary(t) && elemTypeInfo(types_[t].elem).kind == ElemKind::Float;
}
bool TypeTable::isTimeLike(TypeId t) const {
  return isElementary(t) && elemTypeInfo(types_[t].elem).kind == ElemKind::Duration;
}
bool TypeTable::isDateLike(TypeId t) const {
  return isElementary(t) && elemTypeInfo(types_[t].elem).kind == ElemKind::Date;
}

bool TypeTable::isChar(TypeId t) const {
  return isElementary(t) && elemTypeInfo(types_[t].elem).kind == ElemKind::Char;
}

ElemType TypeTable::storageElem(TypeId t) const {
  const bc::TypeDesc& d = types_[t];
  switch (d.kind) {
    case bc::TypeKind::Elementary:
    case bc::TypeKind::Enum: return d.elem;
    case bc::TypeKind::Pointer:
    case bc::TypeKind::Reference: return ElemType::Lword;
    default: return ElemType::Lword;
  }
}

// Integer rank inside its family: bigger rank holds all values of a smaller one.
static int familyRank(ElemType e) {
  switch (e) {
    case ElemType::Sint: case ElemType::Usint: case ElemType::Byte: return 1;
    case ElemType::Int: case ElemType::Uint: case ElemType::Word: return 2;
    case ElemType::Dint: case ElemType::Udint: case ElemType::Dword: return 3;
    case ElemType::Lint: case ElemType::Ulint: case ElemType::Lword: return 4;
    default: return 0;
  }
}

static Conversion integerConversion(ElemType from, ElemType to) {
  ElemKind fk = elemTypeInfo(from).kind, tk = elemTypeInfo(to).kind;
  int fr = familyRank(from), tr = familyRank(to);
  if (fk == tk) return fr <= tr ? Conversion::Widening : Conversion::Narrowing;
  // unsigned/bit-string -> signed needs a strictly wider target
  if (tk == ElemKind::Signed) return fr < tr ? Conversion::Widening : Conversion::Narrowing;
  // signed -> unsigned/bit-string loses negative values
  if (fk == ElemKind::Signed) return Conversion::Narrowing;
  // unsigned <-> bit string of at least the same size
  return fr <= tr ? Conversion::Widening : Conversion::Narrowing;
}

Conversion classifyConversion(const TypeTable& types, TypeId from, TypeId to) {
  if (from == to) return Conversion::Same;
  if (types.isString(from) && types.isString(to))
    return types.isWideString(from) == types.isWideString(to) ? Conversion::Same : Conversion::Invalid;
  if (types.isPointer(from) && types.isPointer(to)) {
    TypeId a = types[from].element, b = types[to].element;
    return (a == b || a == kNoType || b == kNoType) ? Conversion::Same : Conversion::Invalid;
  }
  if (!types.isElementary(from) || !types.isElementary(to)) return Conversion::Invalid;
  ElemType f = types[from].elem, t = types[to].elem;
  if (f == ElemType::Bool || t == ElemType::Bool) {
    // CODESYS converts BOOL to bit strings implicitly, nothing else.
    if (f == ElemType::Bool && types.isBitString(to)) return Conversion::Widening;
    return Conversion::Invalid;
  }
  if (types.isInteger(from) && types.isInteger(to)) return integerConversion(f, t);
  if (types.isInteger(from) && types.isReal(to)) {
    if (t == ElemType::Lreal) return Conversion::Widening;
    return familyRank(f) <= 2 ? Conversion::Widening : Conversion::Narrowing;
  }
  if (types.isReal(from) && types.isReal(to))
    return f == ElemType::Real ? Conversion::Widening : Conversion::Narrowing;
  if (types.isReal(from) && types.isInteger(to)) return Conversion::Narrowing;
  if (types.isTimeLike(from) && types.isTimeLike(to))
    return f == ElemType::Time ? Conversion::Widening : Conversion::Narrowing;
  // IEC 61131-3 ed. 3 (table 12): DATE to LDATE, TOD to LTOD, DT to LDT and CHAR to WCHAR
  // are implicit; the other way loses the fraction / the high byte.
  if (types.isDateLike(from) && types.isDateLike(to) && datePart(f) == datePart(t))
    return elemTypeInfo(f).sizeBytes < elemTypeInfo(t).sizeBytes ? Conversion::Widening : Conversion::Narrowing;
  if (types.isChar(from) && types.isChar(to))
    return f == ElemType::Char ? Conversion::Widening : Conversion::Narrowing;
  return Conversion::Invalid;
}

bool sameType(const TypeTable& types, TypeId a, TypeId b) {
  if (a == b) return true;
  if (a == kNoType || b == kNoType) return false;
  const bc::TypeDesc& x = types[a];
  const bc::TypeDesc& y = types[b];
  if (x.kind != y.kind) return false;
  switch (x.kind) {
    case bc::TypeKind::Elementary: return x.elem == y.elem;
    case bc::TypeKind::String: return x.elem == y.elem && x.stringLength == y.stringLength;
    case bc::TypeKind::Pointer:
    case bc::TypeKind::Reference: return sameType(types, x.element, y.element);
    case bc::TypeKind::Array: {
      if (x.dims.size() != y.dims.size()) return false;
      for (size_t i = 0; i < x.dims.size(); ++i)
        if (x.dims[i].lo != y.dims[i].lo || x.dims[i].hi != y.dims[i].hi) return false;
      return sameType(types, x.element, y.element);
    }
    default: return false;  // structs, enums, FBs: only the same declaration
  }
}

}  // namespace virtcom::st
