// Declaration pass, part 1: names, named types (STRUCT, enums, aliases, subranges) and the
// resolution of written types.
#include <algorithm>

#include "lang/st/declare/declare.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/declare/standard_functions.hpp"

namespace virtcom::st {

std::string configCallerName(std::string_view instanceName) { return "__CONFIG_" + std::string(instanceName); }

Declarer::Declarer(const std::vector<CompilationUnit>& units, Diagnostics& diags, TypeTable& types,
                   ProgramModel& model, ImageBuilder& image, bc::Module& module)
    : units_(units), diags_(diags), types_(types), model_(model), image_(image), module_(module) {}

void Declarer::run() {
  registerNames();
  collectGlobalConstants();  // first: array bounds of located variables may name constants
  allocateProcessAreas();
  declareInterfaces();
  linkInheritance();
  layoutStarted_ = true;  // inheritance is known: FB layouts may now be computed on demand
  declareTypes();
  declarePous();
  declareGlobals();
  checkExternals();
  declareConfiguration();
  // Initial values are checked when a type's default bytes are first built; build them for
  // every named type, so an FB or STRUCT that nothing instantiates (a library) is checked too.
  for (const auto& [name, type] : model_.namedTypes) defaultBytes(type);
}

void Declarer::registerPou(const Pou& pou, uint32_t fileId) {
  std::string key = upper(pou.name);
  if (isStandardFunctionName(key)) {
    diags_.error(diag::E119, pou.loc, "'" + pou.name + "' is the name of a standard function; choose another name");
    return;
  }
  if (model_.pouByName.count(key) || typeDecls_.count(key) || model_.interfaces.count(key)) {
    diags_.error(diag::E105, pou.loc, "'" + pou.name + "' is already declared");
    return;
  }
  auto sym = std::make_unique<PouSym>();
  sym->kind = pou.kind;
  sym->name = pou.name;
  sym->qualifiedName = pou.name;
  sym->ast = &pou;
  sym->fileId = fileId;
  sym->isAbstract = pou.isAbstract;
  for (const auto& i : pou.implements) sym->interfaces.push_back(upper(i));
  model_.pouByName[key] = sym.get();
  if (pou.kind == PouKind::FunctionBlock || pou.kind == PouKind::Program) {
    sym->instanceType = types_.addNamed(bc::TypeKind::Struct, pou.name);
    model_.namedTypes[key] = sym->instanceType;
    model_.fbByType[sym->instanceType] = sym.get();
  }
  model_.pous.push_back(std::move(sym));
}

// CODESYS's implicit base interface __SYSTEM.IQueryInterface has no methods; interfaces extend
// it so that __QUERYINTERFACE may convert them. virtcom converts any interface, so it only has
// to be known (as a base and as a variable type).
void Declarer::registerQueryInterface() {
  static const Interface kQueryInterface{"__SYSTEM.IQueryInterface", {}, {}, {}, {}};
  InterfaceSym sym;
  sym.name = kQueryInterface.name;
  sym.ast = &kQueryInterface;
  model_.interfaces.emplace(upper(sym.name), std::move(sym));
}

void Declarer::registerNames() {
  for (const auto& unit : units_) {
    for (const auto& type : unit.types) {
      std::string key = upper(type.name);
      ElemType elem;
      if (typeDecls_.count(key) || elemTypeByName(key, elem)) {
        diags_.error(diag::E105, type.loc, "type '" + type.name + "' is already declared");
        continue;
      }
      typeDecls_[key] = &type;
    }
    for (const auto& itf : unit.interfaces) {
      std::string key = upper(itf.name);
      if (model_.interfaces.count(key) || typeDecls_.count(key)) {
        diags_.error(diag::E105, itf.loc, "'" + itf.name + "' is already declared");
        continue;
      }
      InterfaceSym sym;
      sym.name = itf.name;
      sym.ast = &itf;
      for (const auto& b : itf.extends) sym.bases.push_back(upper(b));
      model_.interfaces[key] = std::move(sym);
    }
  }
  registerQueryInterface();
  for (const auto& unit : units_)
    for (const auto& pou : unit.pous) registerPou(*pou, unit.fileId);
  for (auto& [key, itf] : model_.interfaces) {
    itf.type = types_.referenceTo(kNoType);
    // Each interface needs its own type id so variables of it can be told apart.
    bc::TypeDesc d = types_[itf.type];
    d.name = itf.name;
    d.kind = bc::TypeKind::Reference;
    TypeId id = types_.addNamed(bc::TypeKind::Reference, itf.name);
    types_.mut(id) = d;
    itf.type = id;
    model_.interfaceByType[id] = &itf;
    model_.namedTypes[key] = id;
  }
}

void Declarer::declareTypes() {
  // Named types get their ids lazily through resolveNamed (so declaration order never matters);
  // force every one of them so errors in unused types are reported too.
  for (const auto& [key, decl] : typeDecls_) {
    TypeSpec named;
    named.kind = TypeSpecKind::Named;
    named.name = decl->name;
    named.loc = decl->loc;
    resolveNamed(named, nullptr);
  }
}

void Declarer::fillTypeDecl(const TypeDecl& decl, TypeId id) {
  const TypeSpec& spec = decl.spec;
  if (spec.kind == TypeSpecKind::Struct) {
    layoutStruct(id, spec.fields, spec.name, spec.isUnion, decl.loc);
  } else if (spec.kind == TypeSpecKind::Enum) {
    fillEnum(id, spec, nullptr);
  }
  if (decl.init) typeInits_[id] = decl.init.get();
}

TypeId Declarer::resolveNamed(const TypeSpec& spec, const PouSym* pou) {
  std::string key(withoutLibraryNamespace(upper(spec.name)));
  ElemType elem;
  if (elemTypeByName(key, elem)) return TypeTable::elem(elem);
  if (auto it = model_.namedTypes.find(key); it != model_.namedTypes.end()) {
    // An FB used as a member or local before its own declaration is laid out first, so the
    // container gets its real size (any declaration order is allowed).
    if (auto fb = model_.fbByType.find(it->second); fb != model_.fbByType.end() && !laidOut_.count(fb->second) && layoutStarted_)
      layoutInstance(*fb->second);
    return it->second;
  }
  auto declIt = typeDecls_.find(key);
  if (declIt == typeDecls_.end()) {
    if (auto p = model_.pouByName.find(key); p != model_.pouByName.end() && p->second->kind == PouKind::Function) {
      diags_.error(diag::E104, spec.loc, "'" + spec.name + "' is a FUNCTION, not a type");
      return kNoType;
    }
    diags_.error(diag::E104, spec.loc, "unknown type '" + spec.name + "'");
    return kNoType;
  }
  const TypeDecl& decl = *declIt->second;
  if (resolving_.count(key)) {
    diags_.error(diag::E112, decl.loc, "type '" + decl.name + "' is defined in terms of itself");
    return kNoType;
  }
  resolving_.insert(key);
  TypeId id = kNoType;
  switch (decl.spec.kind) {
    case TypeSpecKind::Struct:
      id = types_.addNamed(bc::TypeKind::Struct, decl.name);
      model_.namedTypes[key] = id;
      fillTypeDecl(decl, id);
      break;
    case TypeSpecKind::Enum:
      id = types_.addNamed(bc::TypeKind::Enum, decl.name);
      model_.namedTypes[key] = id;
      fillTypeDecl(decl, id);
      break;
    case TypeSpecKind::Subrange: {
      TypeId base = resolveType(*decl.spec.element, pou);
      if (base != kNoType) {
        id = types_.addNamed(bc::TypeKind::Elementary, decl.name);
        bc::TypeDesc d = types_[base];
        d.name = decl.name;
        types_.mut(id) = d;
        auto lo = constant(*decl.spec.lo, pou), hi = constant(*decl.spec.hi, pou);
        if (lo && hi) model_.subranges[id] = {constAsInt(*lo), constAsInt(*hi)};
        model_.namedTypes[key] = id;
        if (decl.init) typeInits_[id] = decl.init.get();
      }
      break;
    }
    default:
      // Aliases (also of arrays, strings and pointers) name an existing type.
      id = resolveType(decl.spec, pou);
      if (id != kNoType && decl.init) {
        // An alias with its own initial value is a distinct type so its default can differ.
        TypeId alias = types_.addNamed(types_[id].kind, decl.name);
        bc::TypeDesc copy = types_[id];
        copy.name = decl.name;
        types_.mut(alias) = copy;
        if (auto sub = model_.subranges.find(id); sub != model_.subranges.end()) model_.subranges[alias] = sub->second;
        id = alias;
        typeInits_[id] = decl.init.get();
      }
      if (id != kNoType) model_.namedTypes[key] = id;
      break;
  }
  resolving_.erase(key);
  return id;
}

TypeId Declarer::resolveType(const TypeSpec& spec, const PouSym* pou) {
  switch (spec.kind) {
    case TypeSpecKind::Named: return resolveNamed(spec, pou);
    case TypeSpecKind::String: {
      uint32_t length = 80;
      if (spec.length) {
        auto v = constant(*spec.length, pou);
        if (!v) return kNoType;
        int64_t n = constAsInt(*v);
        if (n < 1 || n > 65535) {
          diags_.error(diag::E107, spec.length->loc, "string length must be 1..65535, found " + std::to_string(n));
          return kNoType;
        }
        length = static_cast<uint32_t>(n);
      }
      return types_.stringOf(length, spec.wide);
    }
    case TypeSpecKind::Array: {
      TypeId element = resolveType(*spec.element, pou);
      if (element == kNoType) return kNoType;
      std::vector<bc::ArrayDim> dims;
      uint64_t total = types_[element].size;
      for (const auto& r : spec.dims) {
        if (!r.lo || !r.hi) {
          diags_.error(diag::E108, spec.loc, "ARRAY[*] (variable-length arrays) is not supported; give the bounds");
          return kNoType;
        }
        auto lo = constant(*r.lo, pou), hi = constant(*r.hi, pou);
        if (!lo || !hi) return kNoType;
        bc::ArrayDim d{constAsInt(*lo), constAsInt(*hi)};
        if (d.hi < d.lo) {
          diags_.error(diag::E106, r.lo->loc, "array upper bound " + std::to_string(d.hi) + " is below lower bound " + std::to_string(d.lo));
          return kNoType;
        }
        total *= d.count();
        if (total > (256u << 20)) {
          diags_.error(diag::E106, r.lo->loc, "array is larger than 256 MiB");
          return kNoType;
        }
        dims.push_back(d);
      }
      return types_.arrayOf(element, dims);
    }
    case TypeSpecKind::Pointer: {
      TypeId target = resolveType(*spec.element, pou);
      return target == kNoType ? kNoType : types_.pointerTo(target);
    }
    case TypeSpecKind::Reference: {
      TypeId target = resolveType(*spec.element, pou);
      return target == kNoType ? kNoType : types_.referenceTo(target);
    }
    case TypeSpecKind::Subrange: {
      TypeId base = resolveType(*spec.element, pou);
      if (base == kNoType) return kNoType;
      if (!types_.isInteger(base)) {
        diags_.error(diag::E104, spec.loc, "a subrange needs an integer base type");
        return kNoType;
      }
      auto lo = constant(*spec.lo, pou), hi = constant(*spec.hi, pou);
      if (!lo || !hi) return kNoType;
      TypeId id = types_.addNamed(bc::TypeKind::Elementary, "");
      bc::TypeDesc d = types_[base];
      d.name = types_.name(base) + "(" + std::to_string(constAsInt(*lo)) + ".." + std::to_string(constAsInt(*hi)) + ")";
      types_.mut(id) = d;
      model_.subranges[id] = {constAsInt(*lo), constAsInt(*hi)};
      return id;
    }
    case TypeSpecKind::Enum: {
      // Inline enumeration in a variable declaration: an anonymous enum type.
      TypeId id = types_.addNamed(bc::TypeKind::Enum, "__ENUM" + std::to_string(types_.size()));
      fillEnum(id, spec, pou);
      return id;
    }
    case TypeSpecKind::Struct:
      diags_.error(diag::E108, spec.loc, "an inline STRUCT is only allowed inside TYPE ... END_TYPE");
      return kNoType;
  }
  return kNoType;
}

// A UNION is laid out as a STRUCT whose fields all start at offset 0, its size the largest
// field's. It may not overlay an FB instance, interface or reference with other bytes: their
// class ids and addresses must only be written by the compiler's own code.
void Declarer::layoutStruct(TypeId id, const std::vector<VarDecl>& fields, const std::string& base, bool isUnion,
                            SourceLocation loc) {
  uint32_t offset = 0, align = 1, unionSize = 0;
  std::vector<bc::Field> out;
  if (!base.empty()) {
    TypeSpec b;
    b.kind = TypeSpecKind::Named;
    b.name = base;
    b.loc = loc;
    TypeId baseId = resolveNamed(b, nullptr);
    if (baseId != kNoType && types_.isStruct(baseId)) {
      out = types_[baseId].fields;
      offset = types_[baseId].size;
      align = types_[baseId].align;
      if (auto it = fieldInits_.find(baseId); it != fieldInits_.end()) fieldInits_[id] = it->second;
    } else if (baseId != kNoType) {
      diags_.error(diag::E111, loc, "'" + base + "' is not a STRUCT");
    }
  }
  std::set<std::string> seen;
  for (const auto& f : out) seen.insert(upper(f.name));
  for (const auto& decl : fields) {
    TypeId ft = resolveType(decl.type, nullptr);
    // A STRUCT still being laid out (this one, or one that led here) cannot be a member by value.
    TypeId inner = ft;
    while (inner != kNoType && types_[inner].kind == bc::TypeKind::Array) inner = types_[inner].element;
    if (inner != kNoType && types_.isStruct(inner) && !model_.fbByType.count(inner) &&
        resolving_.count(upper(types_[inner].name))) {
      diags_.error(diag::E112, decl.type.loc, "STRUCT '" + types_[inner].name + "' contains itself");
      ft = kNoType;
    }
    for (const auto& n : decl.names) {
      if (!seen.insert(upper(n.name)).second) {
        diags_.error(diag::E105, n.loc, "member '" + n.name + "' is already declared");
        continue;
      }
      if (ft == kNoType) continue;
      if (isUnion && !overlayable(ft)) {
        diags_.error(diag::E108, n.loc, "UNION member '" + n.name + "' cannot be an FB instance, interface or reference");
        continue;
      }
      if (isUnion) offset = 0;
      uint32_t a = std::min<uint32_t>(types_[ft].align, 8);
      offset = (offset + a - 1) / a * a;
      align = std::max(align, a);
      bc::Field field;
      field.name = n.name;
      field.type = ft;
      field.offset = offset;
      if (decl.init) fieldInits_[id].push_back({out.size(), decl.init.get()});
      out.push_back(std::move(field));
      offset += types_[ft].size;
      unionSize = std::max(unionSize, offset);
    }
  }
  if (isUnion) offset = unionSize;
  bc::TypeDesc& d = types_.mut(id);
  d.fields = std::move(out);
  d.align = align;
  d.size = (offset + align - 1) / align * align;
}

bool Declarer::overlayable(TypeId type) const {
  const bc::TypeDesc& d = types_[type];
  if (d.kind == bc::TypeKind::Reference || model_.fbByType.count(type) || model_.interfaceByType.count(type)) return false;
  if (d.kind == bc::TypeKind::Array) return overlayable(d.element);
  if (d.kind == bc::TypeKind::Struct)
    for (const auto& f : d.fields)
      if (!overlayable(f.type)) return false;
  return true;
}

void Declarer::fillEnum(TypeId id, const TypeSpec& spec, const PouSym* pou) {
  ElemType baseElem = ElemType::Int;
  if (!spec.name.empty()) {
    ElemType base;
    if (elemTypeByName(spec.name, base) && isInteger(base)) baseElem = base;
    else diags_.error(diag::E104, spec.loc, "enumeration base type must be an integer type, found '" + spec.name + "'");
  }
  int64_t next = 0;
  std::set<std::string> seen;
  std::vector<bc::Enumerator> values;
  for (const auto& ev : spec.enumValues) {
    if (ev.value)
      if (auto v = constant(*ev.value, pou)) next = constAsInt(*v);
    if (!seen.insert(upper(ev.name)).second)
      diags_.error(diag::E105, ev.loc, "enumeration value '" + ev.name + "' is already declared in '" + types_.name(id) + "'");
    values.push_back({ev.name, next});
    enumerators_[upper(ev.name)].push_back({id, next});
    ++next;
  }
  bc::TypeDesc& d = types_.mut(id);
  d.elem = baseElem;
  d.enumerators = std::move(values);
  d.size = elemTypeInfo(baseElem).sizeBytes;
  d.align = d.size;
}

std::optional<ConstValue> Declarer::enumValue(const std::string& type, const std::string& value) {
  TypeSpec s;
  s.kind = TypeSpecKind::Named;
  s.name = type;
  auto it = model_.namedTypes.find(upper(type));
  TypeId id = it != model_.namedTypes.end() ? it->second : kNoType;
  if (id == kNoType && typeDecls_.count(upper(type))) id = resolveNamed(s, nullptr);
  if (id == kNoType || !types_.isEnum(id)) return std::nullopt;
  for (const auto& e : types_[id].enumerators)
    if (upper(e.name) == upper(value)) {
      ConstValue v;
      v.kind = ConstValue::Kind::Int;
      v.i = e.value;
      return v;
    }
  return std::nullopt;
}

std::optional<ConstValue> Declarer::bareEnumerator(const std::string& name, TypeId& type) {
  auto it = enumerators_.find(upper(name));
  if (it == enumerators_.end() || it->second.size() != 1) return std::nullopt;
  type = it->second[0].first;
  ConstValue v;
  v.kind = ConstValue::Kind::Int;
  v.i = it->second[0].second;
  return v;
}

std::optional<ConstValue> Declarer::lookupConstName(const Expr& e, const PouSym* pou) {
  if (e.kind == ExprKind::Member && e.lhs && e.lhs->kind == ExprKind::Name) {
    // Color.Red (enum) or GVL.kMax (constant in a global list)
    if (auto v = enumValue(e.lhs->text, e.text)) return v;
    if (auto c = globalConstants_.find(upper(e.lhs->text) + "." + upper(e.text)); c != globalConstants_.end()) return c->second;
    auto g = model_.globalIndex.find(upper(e.lhs->text) + "." + upper(e.text));
    if (g != model_.globalIndex.end() && model_.globals[g->second].var.constant &&
        model_.globals[g->second].var.constValue.kind != ConstValue::Kind::None)
      return model_.globals[g->second].var.constValue;
    return std::nullopt;
  }
  if (e.kind != ExprKind::Name) return std::nullopt;
  std::string key = upper(e.text);
  auto fromVar = [](const VarInfo& v) -> std::optional<ConstValue> {
    if (v.constant && v.constValue.kind != ConstValue::Kind::None) return v.constValue;
    return std::nullopt;
  };
  if (pou) {
    if (auto it = pou->localIndex.find(key); it != pou->localIndex.end()) return fromVar(pou->locals[it->second]);
    for (const PouSym* p = pou; p; p = p->owner ? p->owner : nullptr) {
      if (auto it = p->memberIndex.find(key); it != p->memberIndex.end()) return fromVar(p->members[it->second]);
      if (!p->owner) break;
    }
  }
  // A CONSTANT of this POU declared in a block not laid out yet (used as an array bound above it).
  for (const PouSym* p = pou; p; p = p->owner)
    if (auto v = declaredConstant(*p->ast, key, p)) return v;
  if (auto g = model_.globalIndex.find(key); g != model_.globalIndex.end()) return fromVar(model_.globals[g->second].var);
  if (auto c = globalConstants_.find(key); c != globalConstants_.end()) return c->second;
  TypeId t;
  return bareEnumerator(e.text, t);
}

std::optional<ConstValue> Declarer::declaredConstant(const Pou& ast, const std::string& key, const PouSym* pou) {
  for (const auto& block : ast.varBlocks) {
    if (!block.constant) continue;
    for (const auto& decl : block.vars)
      for (const auto& n : decl.names) {
        if (upper(n.name) != key || !decl.init) continue;
        if (!constantsInProgress_.insert(key).second) return std::nullopt;  // defined through itself
        auto v = constant(*decl.init, pou, true);
        constantsInProgress_.erase(key);
        return v;
      }
  }
  return std::nullopt;
}

ConstContext Declarer::constContext(const PouSym* pou) {
  ConstContext ctx;
  ctx.lookupName = [this, pou](const Expr& e) { return lookupConstName(e, pou); };
  ctx.lookupEnum = [this](const std::string& t, const std::string& v) { return enumValue(t, v); };
  return ctx;
}

std::optional<ConstValue> Declarer::constant(const Expr& e, const PouSym* pou, bool quiet) {
  return evalConst(e, constContext(pou), diags_, quiet);
}

}  // namespace virtcom::st
