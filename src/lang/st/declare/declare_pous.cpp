// Declaration pass, part 2: POU interfaces and layouts — FB/PROGRAM instances (with
// inheritance), function and method frames, methods, properties, actions and interfaces.
#include <algorithm>
#include <functional>

#include "lang/st/declare/declare.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/declare/standard_functions.hpp"

namespace virtcom::st {

static bool isInstanceSection(VarSection s) {
  return s == VarSection::Input || s == VarSection::Output || s == VarSection::InOut || s == VarSection::Var ||
         s == VarSection::Inst || s == VarSection::Stat;
}

static uint32_t alignUp(uint32_t v, uint32_t a) { return (v + a - 1) / a * a; }

static bool hasAttribute(const std::vector<Attribute>& attrs, const char* name) {
  for (const auto& a : attrs)
    if (upper(a.name) == name) return true;
  return false;
}

void Declarer::checkVariable(const VarInfo& v) {
  if (isStandardFunctionName(upper(v.name)))
    diags_.error(diag::E119, v.loc, "'" + v.name + "' is the name of a standard function and cannot name a variable");
  if (auto fb = model_.fbByType.find(v.type); fb != model_.fbByType.end() && fb->second->isAbstract)
    diags_.error(diag::E215, v.loc, "'" + fb->second->name + "' is ABSTRACT and cannot be instantiated; declare an instance of a FUNCTION_BLOCK that EXTENDS it");
}

void Declarer::linkInheritance() {
  for (auto& sym : model_.pous) {
    if (sym->kind != PouKind::FunctionBlock || sym->ast->extends.empty()) continue;
    auto it = model_.pouByName.find(upper(sym->ast->extends));
    if (it == model_.pouByName.end() || it->second->kind != PouKind::FunctionBlock) {
      diags_.error(diag::E111, sym->ast->loc, "'" + sym->ast->extends + "' is not a FUNCTION_BLOCK that can be extended");
      continue;
    }
    sym->base = it->second;
    if (it->second->ast->isFinal)
      diags_.error(diag::E218, sym->ast->loc, "'" + it->second->name + "' is FINAL and cannot be extended");
  }
  // Break cycles so later passes can walk bases safely.
  for (auto& sym : model_.pous) {
    std::set<PouSym*> seen;
    for (PouSym* p = sym.get(); p; p = p->base) {
      if (!seen.insert(p).second) {
        diags_.error(diag::E112, sym->ast->loc, "'" + sym->name + "' inherits from itself");
        sym->base = nullptr;
        break;
      }
    }
  }
  for (auto& sym : model_.pous) {
    if (sym->kind != PouKind::FunctionBlock) continue;
    if (sym->base || !sym->interfaces.empty()) {
      for (PouSym* p = sym.get(); p; p = p->base) p->hasClassHeader = true;
    }
    for (const auto& i : sym->interfaces)
      if (!model_.interfaces.count(i)) diags_.error(diag::E113, sym->ast->loc, "unknown INTERFACE '" + i + "'");
  }
}

VarInfo makeVar(const DeclName& n, const VarDecl& decl, TypeId type, VarSection section, const VarBlock& block) {
  VarInfo v;
  v.name = n.name;
  v.loc = n.loc;
  v.type = type;
  v.section = section;
  v.constant = block.constant;
  v.byReference = section == VarSection::InOut;
  v.readOnly = block.constant || hasAttribute(decl.attributes, "ADS_READONLY");
  v.hidden = hasAttribute(decl.attributes, "HIDE");
  v.retain = block.retain || block.persistent;
  v.decl = &decl;
  return v;
}

// An FB instance (member or local) needs its FB laid out first, whatever the declaration order;
// an FB cannot contain itself by value. False (reported) for such a cycle.
bool Declarer::layoutFbOf(const TypeSpec& spec, VarSection section) {
  const TypeSpec* inner = &spec;
  while (inner->kind == TypeSpecKind::Array && inner->element) inner = inner->element.get();
  if (section == VarSection::InOut || inner->kind != TypeSpecKind::Named) return true;
  auto fb = model_.pouByName.find(upper(inner->name));
  if (fb == model_.pouByName.end() || fb->second->kind != PouKind::FunctionBlock) return true;
  for (const PouSym* p = fb->second; p; p = p->base)
    if (layingOut_.count(p)) {
      diags_.error(diag::E112, spec.loc, "FUNCTION_BLOCK '" + fb->second->name + "' contains itself");
      return false;
    }
  layoutInstance(*fb->second);
  return true;
}

void Declarer::addMembers(PouSym& pou, const Pou& ast, bool methodInst) {
  const PouSym* scope = &pou;
  PouSym& target = methodInst ? *pou.owner : pou;
  for (const auto& block : ast.varBlocks) {
    bool member = methodInst ? block.section == VarSection::Inst : isInstanceSection(block.section);
    if (!member) continue;
    for (const auto& decl : block.vars) {
      bool cyclic = !layoutFbOf(decl.type, block.section);
      TypeId type = cyclic ? kNoType : resolveType(decl.type, scope);
      for (const auto& n : decl.names) {
        std::string key = upper(methodInst ? pou.name + "." + n.name : n.name);
        if (target.memberIndex.count(key)) {
          diags_.error(diag::E105, n.loc, "'" + n.name + "' is already declared in '" + target.name + "'");
          continue;
        }
        if (type == kNoType) continue;
        VarInfo v = makeVar(n, decl, type, block.section, block);
        if (methodInst) {
          v.name = pou.name + "." + n.name;
          v.hidden = true;
        }
        if (!decl.location.empty()) {
          placeLocated(v, decl.location);
          bc::Field f;
          f.name = v.name;
          f.type = type;
          f.offset = v.offset;
          f.bit = v.bit;
          f.absolute = true;
          f.section = "VAR";
          types_.mut(target.instanceType).fields.push_back(std::move(f));
        } else {
          v.storage = Storage::Instance;
          uint32_t size = v.byReference ? 8 : types_[type].size;
          uint32_t align = v.byReference ? 8 : std::min<uint32_t>(types_[type].align, 8);
          // Before taking `inst`: referenceTo() may add a type, which moves every TypeDesc.
          const bc::TypeId fieldType = v.byReference ? types_.referenceTo(type) : type;
          bc::TypeDesc& inst = types_.mut(target.instanceType);
          v.offset = alignUp(inst.size, align);
          inst.size = v.offset + size;
          inst.align = std::max(inst.align, align);
          bc::Field f;
          f.name = v.name;
          f.type = fieldType;
          f.offset = v.offset;
          f.hidden = v.hidden;
          f.readOnly = v.readOnly;
          f.retain = v.retain;
          static const char* kSectionNames[] = {"VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP",
                                                "VAR_GLOBAL", "VAR_EXTERNAL", "VAR_INST", "VAR_STAT"};
          f.section = kSectionNames[static_cast<int>(block.section)];
          inst.fields.push_back(std::move(f));
        }
        if (block.constant && types_.isScalar(type) && decl.init)
          if (auto c = constant(*decl.init, scope, true)) v.constValue = *c;
        checkVariable(v);
        const bool edge = !methodInst && decl.edge != EdgeKind::None && edgeAllowed(target, block, decl);
        if (edge) v.edge = decl.edge;
        target.memberIndex[key] = target.members.size();
        target.members.push_back(std::move(v));
        if (edge) addEdgeState(target, target.members.size() - 1);
      }
    }
  }
}

bool Declarer::edgeAllowed(const PouSym& pou, const VarBlock& block, const VarDecl& decl) const {
  bool instance = pou.kind == PouKind::FunctionBlock || pou.kind == PouKind::Program;
  return instance && block.section == VarSection::Input && decl.type.kind == TypeSpecKind::Named &&
         upper(decl.type.name) == "BOOL";
}

void Declarer::checkEdgeDeclarations(const PouSym& pou) {
  for (const auto& block : pou.ast->varBlocks)
    for (const auto& decl : block.vars)
      if (decl.edge != EdgeKind::None && !edgeAllowed(pou, block, decl))
        diags_.error(diag::E108, decl.edgeLoc, std::string(decl.edge == EdgeKind::Rising ? "R_EDGE" : "F_EDGE") +
                                                   " is only allowed on a BOOL VAR_INPUT of a FUNCTION_BLOCK or PROGRAM; "
                                                   "elsewhere use an R_TRIG/F_TRIG instance");
}

// The hidden state of an edge input (IEC 61131-3: an implicit R_TRIG/F_TRIG): the edge the POU's
// code reads, then the input's previous value. Both start FALSE, so a FALSE input on the first
// call is no falling edge (as F_TRIG, whose memory starts TRUE, decides).
void Declarer::addEdgeState(PouSym& pou, size_t inputIndex) {
  const std::string base = pou.members[inputIndex].name;
  pou.members[inputIndex].edgeMember = static_cast<uint32_t>(pou.members.size());
  for (const char* suffix : {"__EDGE", "__PREV"}) {
    VarInfo v = pou.members[inputIndex];
    v.name = "__" + base + suffix;
    v.section = VarSection::Var;
    v.edge = EdgeKind::None;
    v.hidden = true;
    v.readOnly = true;
    v.retain = false;
    v.decl = nullptr;
    v.storage = Storage::Instance;
    v.bit = -1;
    bc::TypeDesc& inst = types_.mut(pou.instanceType);
    v.offset = inst.size;
    inst.size += 1;
    bc::Field f;
    f.name = v.name;
    f.type = v.type;
    f.offset = v.offset;
    f.hidden = true;
    f.readOnly = true;
    f.section = "VAR";
    inst.fields.push_back(std::move(f));
    pou.memberIndex[upper(v.name)] = pou.members.size();
    pou.members.push_back(std::move(v));
  }
}

void Declarer::layoutInstance(PouSym& pou) {
  if (!laidOut_.insert(&pou).second) return;
  layingOut_.insert(&pou);
  bc::TypeDesc& inst = types_.mut(pou.instanceType);
  inst.align = 1;
  if (pou.base) {
    layoutInstance(*pou.base);
    const bc::TypeDesc& base = types_[pou.base->instanceType];
    bc::TypeDesc& self = types_.mut(pou.instanceType);
    self.fields = base.fields;
    self.size = base.size;
    self.align = base.align;
    pou.members = pou.base->members;
    pou.memberIndex = pou.base->memberIndex;
    pou.methods = pou.base->methods;
    pou.properties = pou.base->properties;
  } else if (pou.hasClassHeader) {
    bc::Field header;
    header.name = "__CLASS";
    header.type = TypeTable::elem(ElemType::Udint);
    header.offset = 0;
    header.hidden = true;
    inst.fields.push_back(header);
    inst.size = 8;
    inst.align = 8;
  }
  if (pou.hasClassHeader) {
    pou.classId = nextClassId_++;
    model_.classes.push_back(&pou);
  }
  addMembers(pou, *pou.ast, false);
  declareMethods(pou);
  bc::TypeDesc& done = types_.mut(pou.instanceType);
  done.size = alignUp(std::max<uint32_t>(done.size, 1), done.align);
  layingOut_.erase(&pou);
}

static PouSym* newChild(ProgramModel& model, PouSym& owner, const Pou& ast, PouKind kind, const std::string& name) {
  auto sym = std::make_unique<PouSym>();
  sym->kind = kind;
  sym->name = name;
  sym->qualifiedName = owner.qualifiedName + "." + name;
  sym->ast = &ast;
  sym->fileId = owner.fileId;
  sym->owner = &owner;
  sym->isAbstract = ast.isAbstract || !ast.hasBody;
  sym->isLibrary = owner.isLibrary;
  PouSym* raw = sym.get();
  model.pous.push_back(std::move(sym));
  return raw;
}

void Declarer::declareMethods(PouSym& owner) {
  const Pou& ast = *owner.ast;
  for (const auto& m : ast.methods) {
    PouSym* method = newChild(model_, owner, *m, PouKind::Method, m->name);
    addMembers(*method, *m, true);
    layoutFrame(*method);
    if (auto inherited = owner.methods.find(upper(m->name)); inherited != owner.methods.end() && inherited->second->ast->isFinal)
      diags_.error(diag::E218, m->loc, "METHOD " + m->name + " is FINAL in '" + inherited->second->owner->name + "' and cannot be overridden");
    owner.methods[upper(m->name)] = method;
  }
  for (const auto& a : ast.actions) {
    PouSym* action = newChild(model_, owner, *a, PouKind::Action, a->name);
    owner.actions[upper(a->name)] = action;
  }
  for (const auto& prop : ast.properties) {
    PropertySym ps;
    ps.name = prop.name;
    ps.loc = prop.loc;
    ps.type = resolveType(prop.type, &owner);
    if (prop.getter) {
      ps.getter = newChild(model_, owner, *prop.getter, PouKind::PropertyGet, prop.name + ".GET");
      ps.getter->returnType = ps.type;
      layoutFrame(*ps.getter);
    }
    if (prop.setter) {
      ps.setter = newChild(model_, owner, *prop.setter, PouKind::PropertySet, prop.name + ".SET");
      layoutFrame(*ps.setter);
    }
    owner.properties[upper(prop.name)] = ps;
  }
}

void Declarer::layoutFrame(PouSym& pou) {
  const Pou& ast = *pou.ast;
  uint32_t size = 0;
  auto addLocal = [&](VarInfo v, uint32_t slotSize, uint32_t align) {
    std::string key = upper(v.name);
    if (pou.localIndex.count(key) || pou.memberIndex.count(key)) {
      diags_.error(diag::E105, v.loc, "'" + v.name + "' is already declared in '" + pou.name + "'");
      return;
    }
    v.storage = Storage::Frame;
    v.offset = alignUp(size, align);
    size = v.offset + slotSize;
    pou.localIndex[key] = pou.locals.size();
    pou.locals.push_back(std::move(v));
  };
  bool isCallable = pou.kind == PouKind::Function || pou.kind == PouKind::Method ||
                    pou.kind == PouKind::PropertyGet || pou.kind == PouKind::PropertySet;
  if (pou.kind == PouKind::Function || pou.kind == PouKind::Method) {
    if (ast.hasReturnType) pou.returnType = resolveType(ast.returnType, &pou);
  }
  for (const auto& block : ast.varBlocks) {
    bool inFrame = block.section == VarSection::Temp || (isCallable && block.section != VarSection::Inst &&
                                                         block.section != VarSection::External &&
                                                         block.section != VarSection::Global);
    if (!inFrame) continue;
    for (const auto& decl : block.vars) {
      if (!decl.location.empty()) {
        // A frame exists only during one call: it has no place in the process image.
        diags_.error(diag::E109, decl.loc, "'AT " + decl.location + "' is not allowed here: " +
                                               (block.section == VarSection::Temp ? "a VAR_TEMP" : "a local of a FUNCTION or METHOD") +
                                               " lives only during one call; declare it in VAR of a PROGRAM or FUNCTION_BLOCK, or as a global");
        continue;
      }
      if (!layoutFbOf(decl.type, block.section)) continue;
      TypeId type = resolveType(decl.type, &pou);
      if (type == kNoType) continue;
      for (const auto& n : decl.names) {
        VarInfo v = makeVar(n, decl, type, block.section, block);
        if (block.constant && types_.isScalar(type) && decl.init)
          if (auto c = constant(*decl.init, &pou, true)) v.constValue = *c;
        checkVariable(v);
        uint32_t slot = v.byReference ? 8 : types_[type].size;
        uint32_t align = v.byReference ? 8 : std::min<uint32_t>(types_[type].align, 8);
        addLocal(std::move(v), slot, align);
      }
    }
  }
  if (pou.returnType != kNoType) {
    VarInfo ret;
    ret.name = ast.name;  // a getter returns through the property's name
    ret.loc = ast.loc;
    ret.type = pou.returnType;
    ret.section = VarSection::Output;
    std::string key = upper(ret.name);
    if (!pou.localIndex.count(key)) {
      addLocal(ret, types_[pou.returnType].size, std::min<uint32_t>(types_[pou.returnType].align, 8));
      pou.returnOffset = pou.locals.back().offset;
    }
  }
  if (pou.kind == PouKind::PropertySet) {
    // The value being assigned arrives in a variable named like the property.
    TypeId type = kNoType;
    for (const auto& p : pou.owner->ast->properties)
      if (upper(p.name) == upper(ast.name)) type = resolveType(p.type, pou.owner);
    if (type != kNoType) {
      VarInfo in;
      in.name = ast.name;
      in.loc = ast.loc;
      in.type = type;
      in.section = VarSection::Input;
      addLocal(in, types_[type].size, std::min<uint32_t>(types_[type].align, 8));
    }
  }
  pou.frameSize = alignUp(size, 8);
  for (const auto& v : pou.locals)
    if (v.section == VarSection::Input || v.section == VarSection::Output || v.section == VarSection::InOut)
      if (upper(v.name) != upper(pou.name) || pou.returnType == kNoType) pou.params.push_back(&v);
}

void Declarer::declareInterfaces() {
  for (auto& [key, itf] : model_.interfaces) {
    for (const auto& m : itf.ast->methods) {
      auto sym = std::make_unique<PouSym>();
      sym->kind = PouKind::Method;
      sym->name = m->name;
      sym->qualifiedName = itf.name + "." + m->name;
      sym->ast = m.get();
      sym->isInterfaceMethod = true;
      sym->isAbstract = true;
      layoutFrame(*sym);
      itf.methods[upper(m->name)] = sym.get();
      model_.pous.push_back(std::move(sym));
    }
    for (const auto& p : itf.ast->properties) {
      PropertySym ps;
      ps.name = p.name;
      ps.loc = p.loc;
      ps.type = resolveType(p.type, nullptr);
      itf.properties[upper(p.name)] = ps;
    }
  }
  // Inherit methods of base interfaces.
  std::function<void(InterfaceSym&, InterfaceSym&, int)> inherit = [&](InterfaceSym& into, InterfaceSym& from, int depth) {
    if (depth > 16) return;
    for (const auto& b : from.bases) {
      auto it = model_.interfaces.find(b);
      if (it == model_.interfaces.end()) {
        diags_.error(diag::E113, from.ast->loc, "unknown base INTERFACE '" + b + "'");
        continue;
      }
      for (auto& [mk, m] : it->second.methods) into.methods.emplace(mk, m);
      for (auto& [pk, p] : it->second.properties) into.properties.emplace(pk, p);
      inherit(into, it->second, depth + 1);
    }
  };
  for (auto& [key, itf] : model_.interfaces) inherit(itf, itf, 0);
}

void Declarer::declarePous() {
  std::vector<PouSym*> topLevel;
  for (auto& sym : model_.pous)
    if (!sym->owner && !sym->isInterfaceMethod) topLevel.push_back(sym.get());
  for (auto& sym : model_.pous)
    if (sym->ast && !sym->isInterfaceMethod) checkEdgeDeclarations(*sym);
  for (PouSym* sym : topLevel) {
    switch (sym->kind) {
      case PouKind::FunctionBlock:
      case PouKind::Program:
        layoutInstance(*sym);
        layoutFrame(*sym);
        break;
      case PouKind::Function:
        layoutFrame(*sym);
        for (const auto& b : sym->ast->varBlocks)
          if (b.section == VarSection::Inst || b.section == VarSection::Stat)
            diags_.error(diag::E108, b.loc, "a FUNCTION has no instance: VAR_INST/VAR_STAT are not allowed here");
        break;
      default: break;
    }
  }
  // Interface conformance: every method of every implemented interface must exist, and a
  // concrete FB must implement every ABSTRACT method it inherits.
  for (PouSym* sym : topLevel) {
    if (sym->kind != PouKind::FunctionBlock || sym->isAbstract) continue;
    for (const auto& [mk, m] : sym->methods)
      if (m->isAbstract && !m->isInterfaceMethod)
        diags_.error(diag::E115, sym->ast->loc, "'" + sym->name + "' must implement the ABSTRACT METHOD " + m->name +
                                                    " it inherits from '" + m->owner->name + "'");
    std::vector<std::string> all;
    for (PouSym* p = sym; p; p = p->base) all.insert(all.end(), p->interfaces.begin(), p->interfaces.end());
    for (const auto& i : all) {
      auto it = model_.interfaces.find(i);
      if (it == model_.interfaces.end()) continue;
      for (const auto& [mk, m] : it->second.methods)
        if (!sym->methods.count(mk))
          diags_.error(diag::E115, sym->ast->loc, "'" + sym->name + "' implements '" + it->second.name +
                                                      "' but has no METHOD " + m->name);
    }
  }
}

}  // namespace virtcom::st
