#pragma once
// The semantic type table. It is the module's own type table (bc::TypeDesc), so what the checker
// reasons about is exactly what tools later see; this class adds interning and type predicates.
#include <map>
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::st {

using bc::TypeId;
using bc::kNoType;

class TypeTable {
 public:
  explicit TypeTable(std::vector<bc::TypeDesc>& storage);

  // Elementary types have fixed ids: the ElemType's ordinal (STRING/WSTRING ids are the
  // default-length STRING(80)/WSTRING(80)).
  static TypeId elem(ElemType t) { return static_cast<TypeId>(t); }
  TypeId stringOf(uint32_t length, bool wide);
  TypeId arrayOf(TypeId element, const std::vector<bc::ArrayDim>& dims);
  TypeId pointerTo(TypeId target);      // kNoType target: POINTER TO BYTE-like untyped pointer
  TypeId referenceTo(TypeId target);
  // Adds an empty named struct/enum/FB layout to be filled in later; returns its id.
  TypeId addNamed(bc::TypeKind kind, std::string name);

  const bc::TypeDesc& operator[](TypeId id) const { return types_[id]; }
  bc::TypeDesc& mut(TypeId id) { return types_[id]; }
  size_t size() const { return types_.size(); }

  // Category predicates; an enum counts as its base integer for arithmetic only where IEC allows.
  bool isElementary(TypeId t) const { return types_[t].kind == bc::TypeKind::Elementary; }
  bool isElem(TypeId t, ElemType e) const { return isElementary(t) && types_[t].elem == e; }
  bool isBool(TypeId t) const { return isElem(t, ElemType::Bool); }
  bool isInteger(TypeId t) const;      // SINT..ULINT and BYTE..LWORD
  bool isBitString(TypeId t) const;    // BOOL, BYTE..LWORD
  bool isSignedInt(TypeId t) const;
  bool isReal(TypeId t) const;         // REAL, LREAL
  bool isNumeric(TypeId t) const { return isInteger(t) || isReal(t); }
  bool isTimeLike(TypeId t) const;     // TIME, LTIME
  bool isDateLike(TypeId t) const;     // DATE, TOD, DT, LDATE, LTOD, LDT
  bool isChar(TypeId t) const;         // CHAR, WCHAR
  bool isString(TypeId t) const { return types_[t].kind == bc::TypeKind::String; }
  bool isWideString(TypeId t) const { return isString(t) && types_[t].elem == ElemType::Wstring; }
  bool isEnum(TypeId t) const { return types_[t].kind == bc::TypeKind::Enum; }
  bool isArray(TypeId t) const { return types_[t].kind == bc::TypeKind::Array; }
  bool isStruct(TypeId t) const { return types_[t].kind == bc::TypeKind::Struct; }
  bool isPointer(TypeId t) const { return types_[t].kind == bc::TypeKind::Pointer; }
  bool isReference(TypeId t) const { return types_[t].kind == bc::TypeKind::Reference; }
  // Types held in registers as a value (everything but strings, arrays and structs).
  bool isScalar(TypeId t) const { return !isString(t) && !isArray(t) && !isStruct(t); }
  // The ElemType a scalar is stored as (enum: its base; pointer/reference: LWORD).
  ElemType storageElem(TypeId t) const;
  uint32_t bits(TypeId t) const { return bitWidth(storageElem(t)); }
  const std::string& name(TypeId t) const { return types_[t].name; }

 private:
  std::vector<bc::TypeDesc>& types_;
  std::map<std::pair<uint32_t, bool>, TypeId> strings_;
  std::map<std::string, TypeId> interned_;  // canonical names of arrays/pointers/references
};

// Result of asking whether a value of type `from` may be assigned to `to` implicitly.
enum class Conversion { Same, Widening, Narrowing, Invalid };
Conversion classifyConversion(const TypeTable& types, TypeId from, TypeId to);

// Structural identity: an alias with its own initial value is the same type as its base, an
// array is the same only with the same bounds and the same element type.
bool sameType(const TypeTable& types, TypeId a, TypeId b);

}  // namespace virtcom::st
