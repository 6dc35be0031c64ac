// Code generation: expressions — literals, names, members, indexing, dereference, operators.
#include <algorithm>
#include <cmath>

#include "lang/st/codegen/check.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/lexer.hpp"

namespace virtcom::st {

using bc::Op;

static bool isUnsigned(const TypeTable& t, TypeId id) {
  if (!t.isInteger(id)) return false;
  return !t.isSignedInt(id);
}

Value PouCompiler::literal(const Expr& e, TypeId expected) {
  ConstContext ctx = ctx_.declarer.constContext(&pou_);
  auto c = evalConst(e, ctx, diags());
  if (!c) return Value::error();
  Value v;
  v.kind = Value::Kind::Const;
  v.c = *c;
  v.type = c->type;
  switch (e.kind) {
    case ExprKind::IntLit:
      if (v.type == kNoType) {
        v.untyped = true;
        // An untyped literal takes the expected integer/real type, else the smallest of DINT/LINT.
        if (expected != kNoType && (types().isInteger(expected) || types().isReal(expected)) &&
            (types().isReal(expected) || c->i == static_cast<int64_t>(c->i))) {
          v.type = c->i >= INT32_MIN && c->i <= INT32_MAX ? TypeTable::elem(ElemType::Dint) : TypeTable::elem(ElemType::Lint);
        } else {
          v.type = c->i >= INT32_MIN && c->i <= INT32_MAX ? TypeTable::elem(ElemType::Dint) : TypeTable::elem(ElemType::Lint);
        }
      } else if (!ctx_.declarer.checkRange(v.type, *c, e.loc)) {
        return Value::error();
      }
      break;
    case ExprKind::RealLit:
      if (v.type == kNoType) {
        v.untyped = true;
        v.type = expected != kNoType && types().isElem(expected, ElemType::Real) ? TypeTable::elem(ElemType::Real)
                                                                                : TypeTable::elem(ElemType::Lreal);
      }
      break;
    case ExprKind::StringLit: {
      if (expected != kNoType && types().isChar(expected))
        if (auto ch = characterConstant(*c, types()[expected].elem)) {
          v.c = *ch;
          v.type = ch->type;
          break;
        }
      if (c->kind == ConstValue::Kind::Int) break;  // CHAR#'a'
      size_t chars = e.wide ? utf8ToUtf16(c->s).size() : c->s.size();
      uint32_t len = static_cast<uint32_t>(std::max<size_t>(chars, 1));
      v.type = types().stringOf(len, e.wide);
      break;
    }
    case ExprKind::TimeLit:
      if (v.type == TypeTable::elem(ElemType::Time) && (c->i > INT32_MAX || c->i < INT32_MIN)) {
        diags().error(diag::E117, e.loc, "the duration does not fit TIME (32-bit milliseconds, at most T#24d20h31m23s647ms); use LTIME#");
        return Value::error();
      }
      break;
    case ExprKind::EnumLit: {
      auto it = model().namedTypes.find(upper(e.typePrefix));
      v.type = it != model().namedTypes.end() ? it->second : kNoType;
      break;
    }
    default: break;
  }
  return v;
}

Place PouCompiler::varPlace(const VarInfo& v, uint16_t instanceBase) {
  Place p;
  p.type = v.type;
  p.var = &v;
  p.constant = v.constant;
  p.isInput = v.section == VarSection::Input;
  p.bit = v.bit;
  switch (v.storage) {
    case Storage::Absolute: p.base = kAbsolute; p.offset = v.offset; break;
    case Storage::Instance: p.base = instanceBase; p.offset = v.offset; break;
    case Storage::Frame: p.base = kFp; p.offset = v.offset; break;
  }
  if (v.byReference) {
    // VAR_IN_OUT: the slot holds the address of the actual variable.
    Place slot = p;
    slot.type = TypeTable::elem(ElemType::Lword);
    slot.bit = -1;
    uint16_t addr = load(slot);
    p.base = addr;
    p.offset = 0;
  }
  if (types().isReference(v.type) && !model().interfaceByType.count(v.type)) {
    // REFERENCE TO: used like the referee (interface variables stay references).
    p = referee(p);
    p.var = &v;
  }
  return p;
}

// The referee of the REFERENCE TO stored at `slot`. Writing it writes the referee, not an input.
Place PouCompiler::referee(const Place& slot) {
  Place p;
  p.type = types()[slot.type].element;
  p.base = load(slot);
  p.viaReference = true;
  p.referenceBase = slot.base;
  p.referenceOffset = slot.offset;
  return p;
}

// The slot holding the address of the REFERENCE TO that `referee` came through.
Place PouCompiler::referenceSlot(const Place& referee) {
  Place slot;
  slot.type = TypeTable::elem(ElemType::Lword);
  slot.base = referee.referenceBase;
  slot.offset = referee.referenceOffset;
  return slot;
}

// The POU whose instance `this` points at (the FB itself, or the owner of a method/action).
static PouSym* instanceOwner(PouSym& pou) {
  if (pou.kind == PouKind::FunctionBlock || pou.kind == PouKind::Program) return &pou;
  return pou.owner;
}

std::optional<Place> PouCompiler::namePlace(const Expr& e, bool forWrite) {
  std::string key = upper(e.text);
  if (auto it = pou_.localIndex.find(key); it != pou_.localIndex.end()) return varPlace(pou_.locals[it->second], kThis);
  if (PouSym* owner = instanceOwner(pou_)) {
    if (auto it = owner->memberIndex.find(key); it != owner->memberIndex.end()) {
      const VarInfo& member = owner->members[it->second];
      // Inside its POU an R_EDGE/F_EDGE input reads the edge of this call; writes (and the
      // callers, through inst.x) reach the input itself.
      if (member.edge != EdgeKind::None && !forWrite) return varPlace(owner->members[member.edgeMember], kThis);
      return varPlace(member, kThis);
    }
    // VAR_INST of the running method
    if (pou_.kind == PouKind::Method)
      if (auto it = owner->memberIndex.find(upper(pou_.name) + "." + key); it != owner->memberIndex.end())
        return varPlace(owner->members[it->second], kThis);
  }
  if (auto it = model().globalIndex.find(key); it != model().globalIndex.end())
    return varPlace(model().globals[it->second].var, kAbsolute);
  return std::nullopt;
}

static const VarInfo* findMember(PouSym* fb, const std::string& key) {
  if (!fb) return nullptr;
  auto it = fb->memberIndex.find(key);
  return it == fb->memberIndex.end() ? nullptr : &fb->members[it->second];
}

std::optional<Place> PouCompiler::memberPlace(const Expr& e, bool forWrite) {
  const Expr& lhs = *e.lhs;
  std::string key = upper(e.text);
  if (!key.empty() && key[0] == '%') {
    // Partial access `dw.%B1`, `lw.%W3`, `dw.%D0` (IEC 61131-3 ed. 3): the n-th BYTE/WORD/DWORD
    // of a bit string or integer, counted from the least significant end (memory is little endian).
    auto host = place(lhs, forWrite);
    if (!host) return std::nullopt;
    const ElemType part = key[1] == 'B' ? ElemType::Byte : key[1] == 'W' ? ElemType::Word
                          : key[1] == 'D' ? ElemType::Dword : ElemType::Lword;
    const uint32_t size = bitWidth(part) / 8;
    uint64_t index = 0;
    for (char c : key.substr(2)) index = std::min<uint64_t>(index * 10 + static_cast<uint64_t>(c - '0'), 1u << 20);
    if (!types().isInteger(host->type) || host->bit >= 0 || host->valueBit >= 0) {
      diags().error(diag::E213, e.loc, "partial access needs an integer or bit-string variable, found " + describe(types(), host->type));
      return std::nullopt;
    }
    if ((index + 1) * size > types()[host->type].size) {
      diags().error(diag::E213, e.loc, "'" + e.text + "' does not exist in " + describe(types(), host->type));
      return std::nullopt;
    }
    Place p = *host;
    p.var = nullptr;
    p.viaReference = false;
    p.type = TypeTable::elem(part);
    p.offset += static_cast<uint32_t>(index * size);
    return p;
  }
  // A property read where a place is needed (`r.Pos.x`, `r.Flags.3`); written only whole.
  if (!forWrite) {
    if (auto prop = memberProperty(e)) return valuePlace(*prop);
  } else if (hasProperty(staticTypeOf(lhs), key)) {
    diags().error(diag::E209, e.loc, "'" + e.text + "' is a PROPERTY: a part of its value cannot be written; "
                                     "read it, change the copy and assign the whole value");
    return std::nullopt;
  }
  if (lhs.kind == ExprKind::Name) {
    std::string base = upper(lhs.text);
    PouSym* owner = instanceOwner(pou_);
    bool shadowed = pou_.localIndex.count(base) || (owner && owner->memberIndex.count(base));
    if (!shadowed) {
      if (auto g = model().globalIndex.find(base + "." + key); g != model().globalIndex.end())
        return varPlace(model().globals[g->second].var, kAbsolute);
      for (const auto& inst : model().programInstances) {
        if (upper(inst.name) != base) continue;
        const VarInfo* m = findMember(inst.pou, key);
        if (!m) {
          diags().error(diag::E212, e.loc, "program '" + inst.name + "' has no variable '" + e.text + "'");
          return std::nullopt;
        }
        // A REFERENCE TO or VAR_IN_OUT is followed inside varPlace: it needs the instance's base.
        if (m->storage == Storage::Instance && (m->byReference || types().isReference(m->type)))
          return varPlace(*m, loadConstInt(inst.address));
        Place p = varPlace(*m, kAbsolute);
        if (m->storage == Storage::Instance) p.offset = inst.address + m->offset;
        return p;
      }
    }
  }
  auto basePlace = place(lhs, forWrite);
  if (!basePlace) return std::nullopt;
  TypeId bt = basePlace->type;
  const bc::TypeDesc& d = types()[bt];
  if (d.kind != bc::TypeKind::Struct) {
    diags().error(diag::E212, e.loc, "'" + e.text + "' is not a member: the value is of type " + describe(types(), bt));
    return std::nullopt;
  }
  if (auto fb = model().fbByType.find(bt); fb != model().fbByType.end()) {
    const VarInfo* m = findMember(fb->second, key);
    if (!m) {
      diags().error(diag::E212, e.loc, "'" + fb->second->name + "' has no variable '" + e.text + "'");
      return std::nullopt;
    }
    Place p = *basePlace;
    if (m->storage == Storage::Absolute) return varPlace(*m, kAbsolute);
    uint16_t baseReg = p.base == kAbsolute ? kAbsolute : p.base;
    Place mp;
    if (m->byReference || types().isReference(m->type)) {
      uint16_t inst = addressOf(p);
      mp = varPlace(*m, inst);
    } else {
      mp = varPlace(*m, baseReg);
      mp.offset = p.offset + m->offset;
    }
    mp.isInput = false;  // writing an FB input from outside is how FBs are parameterised
    bool viaThis = lhs.kind == ExprKind::Deref && lhs.lhs && (lhs.lhs->kind == ExprKind::This || lhs.lhs->kind == ExprKind::Super);
    if (forWrite && m->section == VarSection::Output && !viaThis) {
      diags().error(diag::E216, e.loc, "'" + e.text + "' is an output of '" + fb->second->name +
                                           "' and can only be read from outside the instance");
      return std::nullopt;
    }
    return mp;
  }
  for (const auto& f : d.fields) {
    if (upper(f.name) != key) continue;
    Place p = *basePlace;
    p.type = f.type;
    p.offset += f.offset;
    p.var = nullptr;
    p.isInput = false;
    p.viaReference = false;
    if (types().isReference(f.type) && !model().interfaceByType.count(f.type)) p = referee(p);
    return p;
  }
  diags().error(diag::E212, e.loc, "'" + d.name + "' has no member '" + e.text + "'");
  return std::nullopt;
}

std::optional<Place> PouCompiler::indexPlace(const Expr& e, bool forWrite) {
  auto basePlace = place(*e.lhs, forWrite);
  if (!basePlace) return std::nullopt;
  TypeId at = basePlace->type;
  const bc::TypeDesc& d = types()[at];
  if (d.kind == bc::TypeKind::Pointer && d.element != kNoType && e.items.size() == 1)
    return pointerIndexPlace(*basePlace, *e.items[0]);
  if (d.kind == bc::TypeKind::String) {
    if (e.items.size() == 1) return stringIndexPlace(*basePlace, *e.items[0]);
    diags().error(diag::E213, e.loc, "a " + std::string(d.elem == ElemType::Wstring ? "WSTRING" : "STRING") +
                                         " takes one index (the 0-based character offset), found " +
                                         std::to_string(e.items.size()));
    return std::nullopt;
  }
  if (d.kind != bc::TypeKind::Array) {
    diags().error(diag::E213, e.loc, "only arrays, STRINGs and pointers can be indexed; this is " + describe(types(), at));
    return std::nullopt;
  }
  if (e.items.size() != d.dims.size()) {
    diags().error(diag::E213, e.loc, "'" + d.name + "' needs " + std::to_string(d.dims.size()) + " index(es), found " +
                                         std::to_string(e.items.size()));
    return std::nullopt;
  }
  uint32_t elemSize = types()[d.element].size;
  Place p = *basePlace;
  p.type = d.element;
  p.var = nullptr;
  p.viaReference = false;
  CheckedOffset offset;
  uint64_t stride = 1;
  for (size_t k = d.dims.size(); k-- > 0;) {
    if (!addCheckedIndex(*e.items[k], d.dims[k], stride * elemSize, d.name, offset)) return std::nullopt;
    stride *= d.dims[k].count();
  }
  p = offsetPlace(p, offset);
  // An element of an ARRAY OF REFERENCE TO is used like its referee, as a REFERENCE TO variable is.
  if (types().isReference(p.type) && !model().interfaceByType.count(p.type)) p = referee(p);
  return p;
}

// `s[i]` on a STRING(n) / WSTRING(n), as CODESYS has it: the BYTE (WORD) at 0-based character
// offset i, read and written in place. Checked like an array index against the declared
// length (0 <= i < n): the terminator slot and the bytes past it are not characters.
std::optional<Place> PouCompiler::stringIndexPlace(const Place& string, const Expr& index) {
  const bc::TypeDesc& d = types()[string.type];
  const bool wide = d.elem == ElemType::Wstring;
  const bc::ArrayDim chars{0, static_cast<int64_t>(d.stringLength) - 1};
  CheckedOffset offset;
  const std::string what = d.name + " (characters 0.." + std::to_string(chars.hi) + ")";
  if (!addCheckedIndex(index, chars, wide ? 2 : 1, what, offset)) return std::nullopt;
  Place p = string;
  p.type = TypeTable::elem(wide ? ElemType::Word : ElemType::Byte);
  p.var = nullptr;
  p.viaReference = false;
  return offsetPlace(p, offset);
}

// One index into `dim` whose elements lie `stride` bytes apart: a constant one is checked now
// (E213) and folded, a variable one becomes an INDEX (checked at run time, the array fault)
// whose byte offset is added up in a register.
bool PouCompiler::addCheckedIndex(const Expr& index, const bc::ArrayDim& dim, uint64_t stride,
                                  const std::string& what, CheckedOffset& offset) {
  Value idx = expr(index, TypeTable::elem(ElemType::Dint));
  if (!idx.ok()) return false;
  if (!types().isInteger(idx.type) && !types().isEnum(idx.type)) {
    diags().error(diag::E213, index.loc, "an index must be an integer, found " + describe(types(), idx.type));
    return false;
  }
  if (idx.kind == Value::Kind::Const) {
    if (idx.c.i < dim.lo || idx.c.i > dim.hi) {
      diags().error(diag::E213, index.loc, "index " + std::to_string(idx.c.i) + " is outside " + what);
      return false;
    }
    offset.constant += (idx.c.i - dim.lo) * static_cast<int64_t>(stride);
    return true;
  }
  uint16_t r = allocReg();
  emit(Op::INDEX, r, toReg(idx), indexDesc({dim.lo, static_cast<uint32_t>(dim.count()), static_cast<uint32_t>(stride)}));
  if (offset.variable == kNoReg) offset.variable = r;
  else emit(Op::ADD, offset.variable, offset.variable, r);
  return true;
}

// The place `offset` bytes after p.
Place PouCompiler::offsetPlace(Place p, const CheckedOffset& offset) {
  p.offset += static_cast<uint32_t>(offset.constant);
  if (offset.variable == kNoReg) return p;
  uint16_t addr = allocReg();
  if (p.base == kAbsolute) {
    emit(Op::ADD, addr, loadConstInt(p.offset), offset.variable);
    p.offset = 0;
  } else {
    emit(Op::ADD, addr, p.base, offset.variable);
  }
  p.base = addr;
  return p;
}

// `p[i]` on a POINTER TO T, as CODESYS allows: the T at p + i * SIZEOF(T). Not bounds-checked
// (the pointer says nothing about how many Ts follow); an access outside the memory image is
// an invalid pointer fault like any other.
std::optional<Place> PouCompiler::pointerIndexPlace(const Place& pointer, const Expr& index) {
  TypeId element = types()[pointer.type].element;
  Value idx = expr(index, TypeTable::elem(ElemType::Dint));
  if (!idx.ok()) return std::nullopt;
  if (!types().isInteger(idx.type)) {
    diags().error(diag::E213, index.loc, "a pointer index must be an integer, found " + describe(types(), idx.type));
    return std::nullopt;
  }
  uint16_t offset = allocReg(), address = allocReg();
  emit(Op::MUL, offset, toReg(idx), loadConstInt(types()[element].size));
  emit(Op::ADD, address, load(pointer), offset);
  Place p;
  p.type = element;
  p.base = address;
  return p;
}

std::optional<Place> PouCompiler::derefPlace(const Expr& e) {
  const Expr& inner = *e.lhs;
  if (inner.kind == ExprKind::This || inner.kind == ExprKind::Super) {
    PouSym* owner = instanceOwner(pou_);
    if (!owner || owner->kind != PouKind::FunctionBlock) {
      diags().error(diag::E214, e.loc, "THIS^ and SUPER^ are only available inside a FUNCTION_BLOCK");
      return std::nullopt;
    }
    Place p;
    p.base = kThis;
    p.type = owner->instanceType;
    if (inner.kind == ExprKind::Super) {
      if (!owner->base) {
        diags().error(diag::E214, e.loc, "SUPER^ needs a FUNCTION_BLOCK that EXTENDS another");
        return std::nullopt;
      }
      p.type = owner->base->instanceType;
    }
    return p;
  }
  Value v = expr(inner);
  if (!v.ok()) return std::nullopt;
  if (!types().isPointer(v.type) && !types().isReference(v.type)) {
    diags().error(diag::E214, e.loc, "'^' needs a POINTER, found " + describe(types(), v.type));
    return std::nullopt;
  }
  TypeId target = types()[v.type].element;
  if (target == kNoType) {
    diags().error(diag::E214, e.loc, "an untyped pointer cannot be dereferenced");
    return std::nullopt;
  }
  Place p;
  p.type = target;
  p.base = toReg(v);
  p.offset = 0;
  return p;
}

// A value read where a place is needed: aggregates already are in memory, a value in a
// register goes to a temporary.
std::optional<Place> PouCompiler::valuePlace(const Value& v) {
  if (!v.ok() || v.kind == Value::Kind::Void) return std::nullopt;
  if (v.kind == Value::Kind::Addr) return v.place;
  Place tmp = frameTemp(v.type);
  store(tmp, toReg(v));
  return tmp;
}

std::optional<Place> PouCompiler::place(const Expr& e, bool forWrite) {
  switch (e.kind) {
    case ExprKind::Name: {
      auto p = namePlace(e, forWrite);
      if (p) return p;
      if (pou_.kind == PouKind::Function && pou_.returnType == kNoType && upper(e.text) == upper(pou_.name))
        diags().error(diag::E114, e.loc, "FUNCTION '" + pou_.name + "' has no return type, so it has no result to assign; "
                                         "declare one: FUNCTION " + pou_.name + " : INT");
      else
        diags().error(diag::E201, e.loc, "'" + e.text + "' is not declared");
      return p;
    }
    case ExprKind::Member: return memberPlace(e, forWrite);
    case ExprKind::Index: return indexPlace(e, forWrite);
    case ExprKind::Deref: return derefPlace(e);
    case ExprKind::BitAccess: {
      auto host = place(*e.lhs, forWrite);
      if (!host) return std::nullopt;
      if (!types().isInteger(host->type) || host->valueBit >= 0) {
        diags().error(diag::E213, e.loc, "bit access needs an integer or bit-string variable, found " + describe(types(), host->type));
        return std::nullopt;
      }
      if (e.intValue >= types().bits(host->type)) {
        diags().error(diag::E213, e.loc, "bit " + std::to_string(e.intValue) + " does not exist in " + describe(types(), host->type));
        return std::nullopt;
      }
      Place p = *host;
      p.viaReference = false;
      p.bitHost = host->type;
      p.type = TypeTable::elem(ElemType::Bool);
      p.valueBit = static_cast<int8_t>(e.intValue);
      return p;
    }
    case ExprKind::DirectAddr: {
      auto a = parseDirectAddress(e.text);
      if (!a) {
        diags().error(diag::E109, e.loc, directAddressError(e.text));
        return std::nullopt;
      }
      const bc::ProcessArea& area = a->area == 'I' ? ctx_.module.inputs : a->area == 'Q' ? ctx_.module.outputs : ctx_.module.memory;
      Place p;
      p.base = kAbsolute;
      p.offset = area.address + a->byteOffset;
      p.bit = a->bit;
      p.type = TypeTable::elem(a->bit >= 0 ? ElemType::Bool : a->size == 1 ? ElemType::Byte : a->size == 2 ? ElemType::Word : a->size == 4 ? ElemType::Dword : ElemType::Lword);
      return p;
    }
    case ExprKind::Call:  // `GetPos().y`, `F().3`: the result, read only
      if (!forWrite) return valuePlace(expr(e));
      [[fallthrough]];
    default:
      diags().error(diag::E209, e.loc, "this expression does not denote a variable");
      return std::nullopt;
  }
}

static bool isEnumTypeName(ProgramModel& m, TypeTable& t, const std::string& name) {
  auto it = m.namedTypes.find(upper(name));
  return it != m.namedTypes.end() && t.isEnum(it->second);
}

Value PouCompiler::expr(const Expr& e, TypeId expected) {
  switch (e.kind) {
    case ExprKind::IntLit:
    case ExprKind::RealLit:
    case ExprKind::BoolLit:
    case ExprKind::StringLit:
    case ExprKind::TimeLit:
    case ExprKind::DateLit:
    case ExprKind::EnumLit: return literal(e, expected);
    case ExprKind::Unary: return unary(e, expected);
    case ExprKind::Binary: return binary(e, expected);
    case ExprKind::Call: {
      // A call as a statement goes to call() directly; here a value is needed.
      Value v = call(e, expected);
      if (v.kind != Value::Kind::Void) return v;
      diags().error(diag::E202, e.loc, "this call returns no value (its POU has no return type); "
                                       "call it as a statement instead of using it in an expression");
      return Value::error();
    }
    case ExprKind::Name: {
      std::string key = upper(e.text);
      auto p = namePlace(e, false);
      if (p) {
        if (p->var && p->var->constant && p->var->constValue.kind != ConstValue::Kind::None && types().isScalar(p->type)) {
          Value v;
          v.kind = Value::Kind::Const;
          v.type = p->type;
          v.c = p->var->constValue;
          return convert(v, p->type, e.loc);
        }
        Value v;
        v.kind = Value::Kind::Addr;
        v.type = p->type;
        v.place = *p;
        if (types().isScalar(p->type)) return regValue(p->type, load(*p));
        return v;
      }
      if (key == "NULL") return constInt(types().pointerTo(kNoType), 0);
      TypeId enumType = kNoType;
      if (auto c = ctx_.declarer.bareEnumerator(e.text, enumType)) {
        // Prefer the expected enum when the name exists in several enumerations.
        Value v;
        v.kind = Value::Kind::Const;
        v.type = enumType;
        v.c = *c;
        return v;
      }
      if (expected != kNoType && types().isEnum(expected))
        if (auto c = ctx_.declarer.enumValue(types().name(expected), e.text)) {
          Value v;
          v.kind = Value::Kind::Const;
          v.type = expected;
          v.c = *c;
          return v;
        }
      if (PouSym* owner = instanceOwner(pou_))
        if (auto prop = owner->properties.find(key); prop != owner->properties.end())
          return propertyGet(prop->second, Receiver{kThis, owner, nullptr, false}, e.loc);
      diags().error(diag::E201, e.loc, "'" + e.text + "' is not declared");
      return Value::error();
    }
    case ExprKind::Member: {
      if (auto prop = memberProperty(e)) return *prop;
      if (e.lhs->kind == ExprKind::Name && isEnumTypeName(model(), types(), e.lhs->text)) {
        auto c = ctx_.declarer.enumValue(e.lhs->text, e.text);
        if (!c) {
          diags().error(diag::E102, e.loc, "'" + e.lhs->text + "' has no value '" + e.text + "'");
          return Value::error();
        }
        Value v;
        v.kind = Value::Kind::Const;
        v.type = model().namedTypes[upper(e.lhs->text)];
        v.c = *c;
        return v;
      }
      [[fallthrough]];
    }
    case ExprKind::Index:
    case ExprKind::Deref:
    case ExprKind::BitAccess:
    case ExprKind::DirectAddr: {
      auto p = place(e, false);
      if (!p) return Value::error();
      if (types().isScalar(p->type)) return regValue(p->type, load(*p));
      Value v;
      v.kind = Value::Kind::Addr;
      v.type = p->type;
      v.place = *p;
      return v;
    }
    case ExprKind::This:
    case ExprKind::Super: {
      PouSym* owner = instanceOwner(pou_);
      if (!owner || owner->kind != PouKind::FunctionBlock) {
        diags().error(diag::E214, e.loc, "THIS is only available inside a FUNCTION_BLOCK");
        return Value::error();
      }
      uint16_t r = allocReg();
      emit(Op::MOV, r, kThis, 0);
      return regValue(types().pointerTo(owner->instanceType), r);
    }
    case ExprKind::ArrayInit:
    case ExprKind::StructInit:
      diags().error(diag::E108, e.loc, "initialiser lists are only allowed in declarations");
      return Value::error();
    default:
      diags().error(diag::E108, e.loc, "unsupported expression");
      return Value::error();
  }
}

Value PouCompiler::unary(const Expr& e, TypeId expected) {
  if (e.unaryOp == UnaryOp::Neg && e.lhs->kind == ExprKind::IntLit && !e.lhs->typePrefix.empty()) {
    // INT#-32768: the range check applies to the negated value
    ElemType et;
    if (elemTypeByName(e.lhs->typePrefix, et)) {
      Value v = constInt(TypeTable::elem(et), static_cast<int64_t>(0 - e.lhs->intValue));
      if (!ctx_.declarer.checkRange(v.type, v.c, e.lhs->loc)) return Value::error();
      return v;
    }
  }
  Value a = expr(*e.lhs, expected);
  if (!a.ok()) return a;
  TypeTable& t = types();
  if (a.kind == Value::Kind::Const && a.c.kind != ConstValue::Kind::String) {
    Value r = a;
    if (e.unaryOp == UnaryOp::Neg) {
      if (a.c.kind == ConstValue::Kind::Real) r.c.f = -a.c.f;
      else r.c.i = static_cast<int64_t>(0 - static_cast<uint64_t>(a.c.i));
      if (a.untyped) {
        // -2147483648 and friends: keep the literal untyped so it adapts
        r.type = r.c.kind == ConstValue::Kind::Int && (r.c.i < INT32_MIN || r.c.i > INT32_MAX) ? TypeTable::elem(ElemType::Lint) : a.type;
        return r;
      }
      if (!t.isNumeric(a.type) && !t.isTimeLike(a.type)) {
        diags().error(diag::E210, e.loc, "unary '-' needs a number, found " + describe(t, a.type));
        return Value::error();
      }
      return convert(r, a.type, e.loc);
    }
    if (e.unaryOp == UnaryOp::Plus) return a;
    if (t.isBool(a.type)) {
      r.c.i = a.c.i == 0;
      return r;
    }
    if (t.isInteger(a.type)) {
      r.c.i = ~a.c.i;
      return convert(r, a.type, e.loc);
    }
  }
  uint16_t src = toReg(a);
  uint16_t out = allocReg();
  switch (e.unaryOp) {
    case UnaryOp::Plus: return a;
    case UnaryOp::Neg:
      if (t.isReal(a.type)) {
        emit(Op::NEG_F, out, src, 0);
        return regValue(a.type, out);
      }
      if (t.isInteger(a.type) || t.isTimeLike(a.type)) {
        emit(Op::NEG, out, src, 0);
        return wrappedValue(a.type, out);
      }
      diags().error(diag::E210, e.loc, "unary '-' needs a number, found " + describe(t, a.type));
      return Value::error();
    case UnaryOp::Not:
      if (t.isBool(a.type)) {
        emit(Op::LNOT, out, src, 0);
        return regValue(a.type, out);
      }
      if (t.isInteger(a.type)) {
        emit(Op::BNOT, out, src, 0);
        return wrappedValue(a.type, out);
      }
      diags().error(diag::E210, e.loc, "NOT needs a BOOL or a bit string, found " + describe(t, a.type));
      return Value::error();
  }
  return Value::error();
}

Value PouCompiler::shortCircuit(const Expr& e) {
  bool isAnd = e.binaryOp == BinaryOp::AndThen;
  uint16_t out = allocReg();
  uint16_t a = condition(*e.lhs);
  emit(Op::MOV, out, a, 0);
  uint32_t skip = emitJump(isAnd ? Op::JZ : Op::JNZ, out);
  uint16_t b = condition(*e.rhs);
  emit(Op::MOV, out, b, 0);
  patchJump(skip, here());
  return regValue(TypeTable::elem(ElemType::Bool), out);
}

Value PouCompiler::binary(const Expr& e, TypeId expected) {
  if (e.binaryOp == BinaryOp::AndThen || e.binaryOp == BinaryOp::OrElse) return shortCircuit(e);
  bool isCompare = e.binaryOp >= BinaryOp::Lt && e.binaryOp <= BinaryOp::Ne;
  TypeId operandHint = isCompare ? kNoType : expected;
  Value a = expr(*e.lhs, operandHint);
  if (!a.ok()) return a;
  Value b = expr(*e.rhs, a.untyped ? operandHint : a.type);
  if (!b.ok()) return b;
  if (a.untyped && !b.untyped && a.kind == Value::Kind::Const) a = coerce(a, b.type, e.lhs->loc);
  if (!a.ok()) return a;
  if (isCompare) return compare(e, a, b);
  return arithmetic(e, a, b);
}

// `k op x` is `x mirrored(op) k`.
static BinaryOp mirrored(BinaryOp op) {
  switch (op) {
    case BinaryOp::Lt: return BinaryOp::Gt;
    case BinaryOp::Le: return BinaryOp::Ge;
    case BinaryOp::Gt: return BinaryOp::Lt;
    case BinaryOp::Ge: return BinaryOp::Le;
    default: return op;
  }
}

Value PouCompiler::compare(const Expr& e, Value a, Value b) {
  TypeTable& t = types();
  TypeId boolT = TypeTable::elem(ElemType::Bool);
  bool strings = (t.isString(a.type) || (a.kind == Value::Kind::Const && a.c.kind == ConstValue::Kind::String)) &&
                 (t.isString(b.type) || (b.kind == Value::Kind::Const && b.c.kind == ConstValue::Kind::String));
  uint16_t ra, rb = 0;
  std::optional<int16_t> k;  // the right-hand side as an immediate (a K comparison)
  BinaryOp op = e.binaryOp;
  Op lt = Op::LT_I, le = Op::LE_I, eq = Op::EQ, ne = Op::NE;
  if (strings) {
    bool wa = a.type != kNoType && t.isWideString(a.type), wb = b.type != kNoType && t.isWideString(b.type);
    if (wa != wb) {
      diags().error(diag::E210, e.loc, "cannot compare a STRING with a WSTRING; convert one of them");
      return Value::error();
    }
    uint16_t x = toReg(a), y = toReg(b);
    Value cmp = callNative(wa ? wideNative(bc::Native::STR_CMP) : bc::Native::STR_CMP, {x, y}, TypeTable::elem(ElemType::Dint));
    ra = cmp.reg;
    k = 0;
  } else {
    TypeId common = commonType(types(), a, b);
    if (common == kNoType && t.isEnum(a.type) && a.type == b.type) common = a.type;
    if (common == kNoType && (t.isPointer(a.type) || t.isPointer(b.type))) common = TypeTable::elem(ElemType::Lword);
    if (common == kNoType || !t.isScalar(common)) {
      diags().error(diag::E210, e.loc, "cannot compare " + describe(t, a.type) + " with " + describe(t, b.type));
      return Value::error();
    }
    if (a.kind == Value::Kind::Const && b.kind == Value::Kind::Const) {
      auto r = foldBinary(e.binaryOp, a.c, b.c, t.isReal(common));
      if (r) return constInt(boolT, r->i);
    }
    Value ca = t.isPointer(common) || common == a.type ? a : convert(a, common, e.loc);
    Value cb = t.isPointer(common) || common == b.type ? b : convert(b, common, e.loc);
    if (!ca.ok() || !cb.ok()) return Value::error();
    // The K comparisons are signed: fine for every register except unsigned 64-bit ones.
    // DATE, TOD and DT are unsigned 32-bit; LDATE, LTOD and LDT signed (before 1970: negative).
    bool unsignedCompare = isUnsigned(t, common) || (t.isDateLike(common) && t.bits(common) < 64) || t.isPointer(common);
    bool immediates = !t.isReal(common) && !(unsignedCompare && t.bits(common) >= 64);
    if (immediates && smallConst(cb)) {
      k = smallConst(cb);
      ra = toReg(ca);
    } else if (immediates && smallConst(ca)) {
      k = smallConst(ca);
      ra = toReg(cb);
      op = mirrored(op);
    } else {
      ra = toReg(ca);
      rb = toReg(cb);
    }
    if (t.isReal(common)) {
      lt = Op::LT_F;
      le = Op::LE_F;
      eq = Op::EQ_F;
      ne = Op::NE_F;
    } else if (unsignedCompare) {
      lt = Op::LT_U;
      le = Op::LE_U;
    }
  }
  uint16_t out = allocReg();
  if (k) {
    emit(op == BinaryOp::Lt   ? Op::LTK
         : op == BinaryOp::Le ? Op::LEK
         : op == BinaryOp::Gt ? Op::GTK
         : op == BinaryOp::Ge ? Op::GEK
         : op == BinaryOp::Eq ? Op::EQK
                              : Op::NEK,
         out, ra, static_cast<uint16_t>(*k));
    return regValue(boolT, out);
  }
  switch (op) {
    case BinaryOp::Lt: emit(lt, out, ra, rb); break;
    case BinaryOp::Le: emit(le, out, ra, rb); break;
    case BinaryOp::Gt: emit(lt, out, rb, ra); break;
    case BinaryOp::Ge: emit(le, out, rb, ra); break;
    case BinaryOp::Eq: emit(eq, out, ra, rb); break;
    default: emit(ne, out, ra, rb); break;
  }
  return regValue(boolT, out);
}

// DATE/DT hold seconds and TOD milliseconds; TIME is milliseconds. The IEC ed. 3 long types
// (LDATE, LTOD, LDT) and LTIME all count nanoseconds: their differences are LTIME, and they
// move by an LTIME (a TIME operand widens to it).
Value PouCompiler::dateArithmetic(const Expr& e, Value a, Value b) {
  TypeTable& t = types();
  const bool isLong = t.isDateLike(a.type) && t[a.type].size == 8;
  TypeId timeT = TypeTable::elem(isLong ? ElemType::Ltime : ElemType::Time);
  // the date's unit in units of its duration type: 1000 for DATE/DT (s vs ms), else 1
  const int64_t ratio = t.isDateLike(a.type) ? timeUnitNs(t[a.type].elem) / timeUnitNs(t[timeT].elem) : 1;
  bool sub = e.binaryOp == BinaryOp::Sub;
  if (sub && a.type == b.type && t.isDateLike(a.type)) {
    uint16_t x = toReg(a), y = toReg(b), r = allocReg();
    emit(Op::SUB, r, x, y);
    if (ratio > 1) emit(Op::MUL, r, r, loadConstInt(ratio));
    normalize(r, timeT);
    return regValue(timeT, r);
  }
  if (t.isDateLike(a.type) && (t.isTimeLike(b.type) || b.untyped)) {
    Value tb = coerce(b, timeT, e.rhs ? e.rhs->loc : e.loc);
    if (!tb.ok()) return tb;
    uint16_t x = toReg(a), y = toReg(tb), r = allocReg();
    if (ratio > 1) {
      uint16_t k = loadConstInt(ratio), q = allocReg();
      emit(Op::DIV_I, q, y, k);
      y = q;
    }
    emit(sub ? Op::SUB : Op::ADD, r, x, y);
    normalize(r, a.type);
    return regValue(a.type, r);
  }
  diags().error(diag::E210, e.loc, "operator cannot combine " + describe(t, a.type) + " and " + describe(t, b.type));
  return Value::error();
}

// Pointer arithmetic as CODESYS has it (OSCAT depends on it): `p + n`, `n + p`, `p - n` move
// the address by n bytes, not n elements (`p + SIZEOF(x)`), and keep p's type; `p - q` is the
// distance in bytes. Nothing is checked here: dereferencing outside the PLC's memory is the
// `invalid pointer access` fault.
Value PouCompiler::pointerArithmetic(const Expr& e, Value a, Value b) {
  TypeTable& t = types();
  const BinaryOp op = e.binaryOp;
  if (op == BinaryOp::Sub && t.isPointer(a.type) && t.isPointer(b.type) && !a.untyped && !b.untyped)
    return pointerDistance(a, b);
  // An untyped literal took the other operand's type when it was evaluated: `1 + p`.
  const bool pointerFirst = t.isPointer(a.type) && !a.untyped;
  const Value& pointer = pointerFirst ? a : b;
  Value offset = pointerFirst ? b : a;
  if (offset.untyped && offset.kind == Value::Kind::Const && offset.c.kind == ConstValue::Kind::Int)
    offset.type = TypeTable::elem(ElemType::Lint);
  if (!t.isInteger(offset.type) || (op != BinaryOp::Add && !(op == BinaryOp::Sub && pointerFirst))) {
    auto what = [&](const Value& v) {
      return v.untyped && v.kind == Value::Kind::Const ? std::string("a literal") : describe(t, v.type);
    };
    diags().error(diag::E210, e.loc, "pointer arithmetic takes a pointer and an integer number of bytes (p + n, n + p, "
                                     "p - n) or two pointers (p - q); found " + what(a) + " and " + what(b));
    return Value::error();
  }
  uint16_t base = toReg(pointer);
  uint16_t bytes = toReg(convert(offset, TypeTable::elem(ElemType::Lint), e.loc));
  uint16_t out = allocReg();
  emit(op == BinaryOp::Add ? Op::ADD : Op::SUB, out, base, bytes);
  Value v = regValue(pointer.type, out);
  v.untypedAddress = pointer.untypedAddress;
  return v;
}

// `p - q` of any two pointers: how many bytes p lies after q, as a LINT (negative when before).
// CODESYS subtracts in its unsigned address type (__UXINT), which gives the same bits.
Value PouCompiler::pointerDistance(Value a, Value b) {
  uint16_t x = toReg(a);
  uint16_t y = toReg(b);
  uint16_t out = allocReg();
  emit(Op::SUB, out, x, y);
  return regValue(TypeTable::elem(ElemType::Lint), out);
}

Value PouCompiler::arithmetic(const Expr& e, Value a, Value b) {
  TypeTable& t = types();
  BinaryOp op = e.binaryOp;
  bool logical = op == BinaryOp::And || op == BinaryOp::Or || op == BinaryOp::Xor;
  // TIME arithmetic: TIME +- TIME, TIME */ ANY_NUM
  if (t.isTimeLike(a.type) && !t.isTimeLike(b.type) && (op == BinaryOp::Mul || op == BinaryOp::Div) && t.isNumeric(b.type)) {
    Value bb = t.isReal(b.type) ? b : convert(b, a.type, e.loc);
    if (t.isReal(b.type)) {
      uint16_t x = toReg(convert(a, TypeTable::elem(ElemType::Lreal), e.loc));
      uint16_t y = toReg(convert(b, TypeTable::elem(ElemType::Lreal), e.loc));
      uint16_t out = allocReg();
      emit(op == BinaryOp::Mul ? Op::MUL_F : Op::DIV_F, out, x, y);
      return convert(regValue(TypeTable::elem(ElemType::Lreal), out), a.type, e.loc);
    }
    b = bb;
  }
  if ((t.isDateLike(a.type) || t.isDateLike(b.type)) && (op == BinaryOp::Add || op == BinaryOp::Sub))
    return dateArithmetic(e, a, b);
  if (t.isPointer(a.type) || t.isPointer(b.type)) return pointerArithmetic(e, a, b);
  if (op == BinaryOp::Power) {
    TypeId rt = t.isElem(a.type, ElemType::Lreal) || t.isElem(b.type, ElemType::Lreal) ? TypeTable::elem(ElemType::Lreal)
                                                                                      : TypeTable::elem(ElemType::Real);
    if (!t.isNumeric(a.type) || !t.isNumeric(b.type)) {
      diags().error(diag::E210, e.loc, "'**' needs numbers");
      return Value::error();
    }
    uint16_t x = toReg(convert(a, TypeTable::elem(ElemType::Lreal), e.loc));
    uint16_t y = toReg(convert(b, TypeTable::elem(ElemType::Lreal), e.loc));
    Value r = callNative(bc::Native::EXPT, {x, y}, TypeTable::elem(ElemType::Lreal));
    return convert(r, rt, e.loc);
  }
  TypeId common = commonType(types(), a, b);
  bool ok = common != kNoType &&
            (logical ? (t.isBitString(common) || t.isInteger(common))
                     : ((t.isNumeric(common) || t.isTimeLike(common)) && !(op == BinaryOp::Mod && t.isReal(common))));
  if (!ok) {
    diags().error(diag::E210, e.loc, "operator cannot combine " + describe(t, a.type) + " and " + describe(t, b.type));
    return Value::error();
  }
  Value ca = convert(a, common, e.loc), cb = convert(b, common, e.loc);
  if (!ca.ok() || !cb.ok()) return Value::error();
  bool real = t.isReal(common);
  if (ca.kind == Value::Kind::Const && cb.kind == Value::Kind::Const) {
    auto r = foldBinary(op, ca.c, cb.c, real);
    if (!r) {
      diags().error(diag::E103, e.loc, "division by zero in a constant expression");
      return Value::error();
    }
    Value v;
    v.kind = Value::Kind::Const;
    v.c = *r;
    v.type = common;
    v.untyped = a.untyped && b.untyped;
    if (v.untyped && r->kind == ConstValue::Kind::Int) {
      // Literals alone compute exactly, like one literal: the target takes the value or reports
      // E117, whatever its size (2147483647 + 1 is out of range for DINT as 127 + 1 is for SINT).
      v.type = TypeTable::elem(r->i >= INT32_MIN && r->i <= INT32_MAX ? ElemType::Dint : ElemType::Lint);
      return v;
    }
    return convert(v, common, e.loc);
  }
  if (!real && (op == BinaryOp::Add || op == BinaryOp::Sub) && cb.kind == Value::Kind::Const) {
    // x + k / x - k with a small k: one ADDI instead of loading the constant
    int64_t k = op == BinaryOp::Add ? cb.c.i : -cb.c.i;
    if (k >= INT16_MIN && k <= INT16_MAX) {
      uint16_t x = rawReg(ca), out = allocReg();
      emit(Op::ADDI, out, x, static_cast<uint16_t>(static_cast<int16_t>(k)));
      return wrappedValue(common, out);
    }
  }
  bool uns = isUnsigned(t, common);
  if (!real && (op == BinaryOp::Div || op == BinaryOp::Mod) && cb.kind == Value::Kind::Const &&
      cb.c.kind == ConstValue::Kind::Int && cb.c.i >= 1 && cb.c.i <= 0xffff && !(uns && t.bits(common) >= 64)) {
    // A positive constant divisor: no zero check, and signed division is right for every
    // register except an unsigned 64-bit one; the result never needs re-extending.
    uint16_t x = toReg(ca), out = allocReg();
    emit(op == BinaryOp::Div ? Op::DIVK : Op::MODK, out, x, static_cast<uint16_t>(cb.c.i));
    return regValue(common, out);
  }
  // The low bits of + - * AND OR XOR depend only on the operands' low bits; / and MOD need
  // extended operands.
  bool lowBits = !real && op != BinaryOp::Div && op != BinaryOp::Mod;
  uint16_t x = lowBits ? rawReg(ca) : toReg(ca), y = lowBits ? rawReg(cb) : toReg(cb);
  uint16_t out = allocReg();
  bool f32 = t.isElem(common, ElemType::Real);
  switch (op) {
    case BinaryOp::Add: emit(real ? (f32 ? Op::ADD_F32 : Op::ADD_F) : Op::ADD, out, x, y); break;
    case BinaryOp::Sub: emit(real ? (f32 ? Op::SUB_F32 : Op::SUB_F) : Op::SUB, out, x, y); break;
    case BinaryOp::Mul: emit(real ? (f32 ? Op::MUL_F32 : Op::MUL_F) : Op::MUL, out, x, y); break;
    case BinaryOp::Div: emit(real ? (f32 ? Op::DIV_F32 : Op::DIV_F) : uns ? Op::DIV_U : Op::DIV_I, out, x, y); break;
    case BinaryOp::Mod: emit(uns ? Op::MOD_U : Op::MOD_I, out, x, y); break;
    case BinaryOp::And: emit(Op::BAND, out, x, y); break;
    case BinaryOp::Or: emit(Op::BOR, out, x, y); break;
    case BinaryOp::Xor: emit(Op::BXOR, out, x, y); break;
    default:
      diags().error(diag::E210, e.loc, "unsupported operator");
      return Value::error();
  }
  // Bitwise operations on extended operands give an extended result. A remainder and an
  // unsigned quotient are never larger than the dividend; a signed quotient overflows only
  // for MIN / -1.
  bool quotientFits = op == BinaryOp::Div && (uns || (cb.kind == Value::Kind::Const && cb.c.i != -1));
  if (real || op == BinaryOp::Mod || quotientFits || (logical && !ca.wrapped && !cb.wrapped))
    return regValue(common, out);
  return wrappedValue(common, out);
}

}  // namespace virtcom::st
