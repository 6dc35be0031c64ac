// Code generation: calls of FUNCTIONs, FUNCTION_BLOCK instances, METHODs (with dynamic dispatch
// through class ids for inheritance and interfaces), ACTIONs and PROPERTY accessors.
#include <algorithm>
#include <set>

#include "lang/st/codegen/check.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/st/declare/standard_functions.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Op;

bool PouCompiler::passesAddress(const VarInfo& p) {
  return p.byReference || (p.section == VarSection::Input && types().isReference(p.type) &&
                           !model().interfaceByType.count(p.type));
}

std::vector<const VarInfo*> PouCompiler::fbParams(PouSym& fb) {
  std::vector<const VarInfo*> out;
  for (const auto& m : fb.members)
    if (m.section == VarSection::Input || m.section == VarSection::Output || m.section == VarSection::InOut)
      out.push_back(&m);
  return out;
}

static bool denotesVariable(const Expr& e) {
  switch (e.kind) {
    case ExprKind::Name: case ExprKind::Member: case ExprKind::Index: case ExprKind::Deref:
    case ExprKind::BitAccess: case ExprKind::DirectAddr:
      return true;
    default:
      return false;
  }
}

void PouCompiler::evaluateInputs(const std::vector<const VarInfo*>& params, std::vector<Binding>& bindings) {
  for (auto& b : bindings) {
    const VarInfo& p = *params[b.param];
    const CallArg& arg = *b.arg;
    if (p.section == VarSection::Output) continue;
    if (!arg.value) continue;
    if (passesAddress(p)) {
      TypeId wanted = p.byReference ? p.type : types()[p.type].element;
      // VAR_IN_OUT CONSTANT (CODESYS) is never written: it also takes constants, literals and
      // expressions, passed as the address of a temporary copy.
      const bool readOnly = p.byReference && p.constant;
      if (readOnly && !denotesVariable(*arg.value)) {
        Place copy = frameTemp(wanted);
        assignValue(copy, expr(*arg.value, wanted), arg.loc);
        b.address = addressOf(copy);
        continue;
      }
      auto target = place(*arg.value, !readOnly);
      if (!target) continue;
      if (!checkInOutActual(diags(), model(), types(), p, wanted, *target, arg.loc)) continue;
      b.address = addressOf(*target);
      continue;
    }
    Value v = expr(*arg.value, p.type);
    if (v.ok() && types().isScalar(p.type) && !model().interfaceByType.count(p.type)) v = coerce(v, p.type, arg.loc);
    else if (v.ok() && v.kind == Value::Kind::Reg && !types().isScalar(v.type)) v.kind = Value::Kind::Reg;
    b.value = v;
  }
}

uint16_t PouCompiler::emitFrameCall(PouSym& callee, uint16_t thisReg) {
  uint16_t frame = allocReg();
  uint16_t self = allocReg();
  emitBx(Op::ENTER, frame, callee.bcIndex);
  if (thisReg != 0xffff) emit(Op::MOV, self, thisReg, 0);
  return frame;
}

static Place frameSlot(const VarInfo& p, uint16_t frameReg) {
  Place slot;
  slot.base = frameReg;
  slot.offset = p.offset;
  slot.type = p.byReference ? TypeTable::elem(ElemType::Lword) : p.type;
  return slot;
}

void PouCompiler::readOutputs(uint16_t base, const std::vector<Binding>& bindings, const std::vector<const VarInfo*>& params) {
  for (const auto& b : bindings) {
    const VarInfo& p = *params[b.param];
    if (p.section != VarSection::Output || !b.arg || !b.arg->value) continue;
    auto target = place(*b.arg->value, true);
    if (!target) continue;
    Place src = frameSlot(p, base);
    Value v;
    if (types().isScalar(p.type)) {
      v = regValue(p.type, load(src));
      if (b.arg->negated) {
        uint16_t r = allocReg();
        emit(Op::LNOT, r, v.reg, 0);
        v.reg = r;
      }
    } else {
      v.kind = Value::Kind::Addr;
      v.type = p.type;
      v.place = src;
    }
    assignValue(*target, v, b.arg->loc);
  }
}

Value PouCompiler::returnValue(PouSym& callee, uint16_t frameReg) {
  if (callee.returnType == kNoType) {
    Value v;
    v.kind = Value::Kind::Void;
    return v;
  }
  Place src;
  src.base = frameReg;
  src.offset = callee.returnOffset;
  src.type = callee.returnType;
  if (types().isScalar(callee.returnType)) return regValue(callee.returnType, load(src));
  // Aggregates are copied out before the next call reuses the callee's frame.
  Place tmp = frameTemp(callee.returnType);
  uint16_t dst = addressOf(tmp);
  uint16_t from = addressOf(src);
  copyBytes(dst, from, types()[callee.returnType].size);
  Value v;
  v.kind = Value::Kind::Addr;
  v.type = callee.returnType;
  v.place = tmp;
  return v;
}

// Stores the evaluated arguments into the callee's frame (functions, methods) or instance (FBs).
static void storeInputs(PouCompiler& pc, const std::vector<const VarInfo*>& params,
                        const std::vector<PouCompiler::Binding>& bindings, uint16_t base) {
  for (const auto& b : bindings) {
    const VarInfo& p = *params[b.param];
    if (p.section == VarSection::Output) continue;
    Place slot = frameSlot(p, base);
    if (pc.passesAddress(p)) {
      slot.type = TypeTable::elem(ElemType::Lword);
      if (b.address != 0xffff) pc.store(slot, b.address);
      continue;
    }
    if (b.value.ok()) pc.assignValue(slot, b.value, b.arg->loc);
  }
}

Value PouCompiler::callFunction(PouSym& fn, const Expr& e) {
  pou_.callees.push_back(&fn);
  std::vector<Binding> bindings;
  if (!bindArguments(diags(), e, fn.params, &fn, bindings)) return Value::error();
  evaluateInputs(fn.params, bindings);
  uint16_t frame = emitFrameCall(fn, 0xffff);
  storeInputs(*this, fn.params, bindings, frame);
  emitBx(Op::CALL, frame, fn.bcIndex);
  Value result = returnValue(fn, frame);
  readOutputs(frame, bindings, fn.params);
  return result;
}

// The VM's native implementation of a standard FB (bytecode/native_fbs.def) if the prelude
// declares exactly the layout the native expects; nullopt for every other FB.
static std::optional<bc::NativeFb> nativeFb(const PouSym& fb, const TypeTable& types) {
  if (!fb.isLibrary || fb.hasClassHeader || fb.base) return std::nullopt;
  const std::string name = upper(fb.name);
  for (uint16_t k = 0; k < static_cast<uint16_t>(bc::NativeFb::Count_); ++k) {
    const auto f = static_cast<bc::NativeFb>(k);
    if (bc::nativeFbName(f) != name) continue;
    const auto members = bc::nativeFbMembers(f);
    if (members.size() != fb.members.size()) return std::nullopt;
    for (size_t j = 0; j < members.size(); ++j) {
      const VarInfo& v = fb.members[j];
      if (upper(v.name) != members[j].name || v.storage != Storage::Instance || v.byReference || v.bit >= 0 ||
          v.offset != members[j].offset || types[v.type].size != members[j].size)
        return std::nullopt;
    }
    return f;
  }
  return std::nullopt;
}

Value PouCompiler::callFbInstance(const Place& inst, PouSym& fb, const Expr& e) {
  pou_.callees.push_back(&fb);
  std::vector<const VarInfo*> params = fbParams(fb);
  std::vector<Binding> bindings;
  if (!bindArguments(diags(), e, params, &fb, bindings)) return Value::error();
  evaluateInputs(params, bindings);
  uint16_t self = addressOf(inst);
  storeInputs(*this, params, bindings, self);
  if (auto native = nativeFb(fb, types())) {
    emitBx(Op::CALLFB, self, static_cast<uint32_t>(*native));
  } else {
    uint16_t frame = emitFrameCall(fb, self);
    emitBx(Op::CALL, frame, fb.bcIndex);
  }
  readOutputs(self, bindings, params);
  Value v;
  v.kind = Value::Kind::Void;
  return v;
}

Value PouCompiler::callAction(PouSym& action, uint16_t thisReg) {
  pou_.callees.push_back(&action);
  uint16_t frame = emitFrameCall(action, thisReg);
  emitBx(Op::CALL, frame, action.bcIndex);
  Value v;
  v.kind = Value::Kind::Void;
  return v;
}

std::vector<std::pair<uint32_t, PouSym*>> PouCompiler::dispatchTargets(const Receiver& recv, const std::string& key,
                                                                      bool property, bool setter) {
  auto implOf = [&](PouSym* c) -> PouSym* {
    if (property) {
      auto it = c->properties.find(key);
      if (it == c->properties.end()) return nullptr;
      return setter ? it->second.setter : it->second.getter;
    }
    auto it = c->methods.find(key);
    return it == c->methods.end() ? nullptr : it->second;
  };
  std::vector<std::pair<uint32_t, PouSym*>> out;
  if (recv.exact || (recv.staticClass && !recv.staticClass->hasClassHeader)) {
    if (PouSym* m = implOf(recv.staticClass)) out.push_back({0, m});
    return out;
  }
  for (PouSym* c : model().classes) {
    bool candidate = recv.viaInterface ? implementsInterface(model(), c, upper(recv.viaInterface->name))
                                       : derivesFrom(c, recv.staticClass);
    if (!candidate || c->isAbstract) continue;
    if (PouSym* m = implOf(c)) out.push_back({c->classId, m});
  }
  return out;
}

// Emits `callOne(target)` for each dispatch target, selected at run time by the class id stored in
// the first 4 bytes of the instance; a single target is called directly. Loading the class id
// also checks the receiver: a null interface or pointer faults at the call, as in CODESYS, even
// when the method itself would not touch the instance.
template <typename F>
static void emitDispatch(PouCompiler& pc, const PouCompiler::Receiver& recv,
                         const std::vector<std::pair<uint32_t, PouSym*>>& targets, F callOne) {
  std::set<PouSym*> distinct;
  for (const auto& t : targets) distinct.insert(t.second);
  bool mayBeNull = !recv.exact && recv.thisReg != kThis;
  bool dynamic = distinct.size() > 1;
  uint16_t cls = 0;
  if (dynamic || mayBeNull) {
    cls = pc.allocReg();
    pc.emit(Op::LD_U32, cls, recv.thisReg, 0);
  }
  if (!dynamic) {
    callOne(*targets.front().second);
    return;
  }
  std::vector<uint32_t> toEnd;
  for (size_t i = 0; i < targets.size(); ++i) {
    uint32_t skip = 0;
    bool last = i + 1 == targets.size();
    if (!last) {
      uint16_t k = pc.loadConstInt(targets[i].first);
      uint16_t eq = pc.allocReg();
      pc.emit(Op::NE, eq, cls, k);
      skip = pc.emitJump(Op::JNZ, eq);
    }
    callOne(*targets[i].second);
    if (!last) {
      toEnd.push_back(pc.emitJump(Op::JMP, 0));
      pc.patchJump(skip, pc.here());
    }
  }
  for (uint32_t j : toEnd) pc.patchJump(j, pc.here());
}

Value PouCompiler::callMethod(const std::string& name, const Receiver& recv, const Expr& e) {
  std::string key = upper(name);
  auto targets = dispatchTargets(recv, key, false, false);
  if (targets.empty()) {
    // interface prototype exists but no class implements it: still type-check
    diags().error(diag::E206, e.loc, "no implementation of METHOD '" + name + "' is available for this call");
    return Value::error();
  }
  PouSym& proto = *targets.front().second;
  if (!checkMethodAccess(diags(), pou_, proto, e.loc)) return Value::error();
  std::vector<Binding> bindings;
  if (!bindArguments(diags(), e, proto.params, &proto, bindings)) return Value::error();
  evaluateInputs(proto.params, bindings);
  uint16_t resultReg = allocReg();
  TypeId rt = proto.returnType;
  bool scalarResult = rt != kNoType && types().isScalar(rt);
  Place aggregate;
  if (rt != kNoType && !scalarResult) aggregate = frameTemp(rt);
  uint16_t aggregateAddr = rt != kNoType && !scalarResult ? addressOf(aggregate) : 0;
  emitDispatch(*this, recv, targets, [&](PouSym& m) {
    pou_.callees.push_back(&m);
    uint16_t inner = regMark();
    uint16_t frame = emitFrameCall(m, recv.thisReg);
    storeInputs(*this, m.params, bindings, frame);
    emitBx(Op::CALL, frame, m.bcIndex);
    if (rt != kNoType) {
      Place src;
      src.base = frame;
      src.offset = m.returnOffset;
      src.type = rt;
      if (scalarResult) emit(Op::MOV, resultReg, load(src), 0);
      else copyBytes(aggregateAddr, addressOf(src), types()[rt].size);
    }
    readOutputs(frame, bindings, m.params);
    freeRegs(inner);
  });
  if (rt == kNoType) {
    Value v;
    v.kind = Value::Kind::Void;
    return v;
  }
  if (scalarResult) return regValue(rt, resultReg);
  Value v;
  v.kind = Value::Kind::Addr;
  v.type = rt;
  v.place = aggregate;
  return v;
}

Value PouCompiler::propertyGet(const PropertySym& prop, const Receiver& recv, SourceLocation loc) {
  uint16_t thisReg = recv.thisReg;
  auto targets = dispatchTargets(recv, upper(prop.name), true, false);
  if (targets.empty()) {
    diags().error(diag::E209, loc, "property '" + prop.name + "' has no GET accessor");
    return Value::error();
  }
  uint16_t result = allocReg();
  bool scalar = types().isScalar(prop.type);
  Place aggregate;
  if (!scalar) aggregate = frameTemp(prop.type);
  emitDispatch(*this, recv, targets, [&](PouSym& getter) {
    pou_.callees.push_back(&getter);
    uint16_t inner = regMark();
    uint16_t frame = emitFrameCall(getter, thisReg);
    emitBx(Op::CALL, frame, getter.bcIndex);
    Place src;
    src.base = frame;
    src.offset = getter.returnOffset;
    src.type = prop.type;
    if (scalar) emit(Op::MOV, result, load(src), 0);
    else copyBytes(addressOf(aggregate), addressOf(src), types()[prop.type].size);
    freeRegs(inner);
  });
  if (scalar) return regValue(prop.type, result);
  Value v;
  v.kind = Value::Kind::Addr;
  v.type = prop.type;
  v.place = aggregate;
  return v;
}

TypeId PouCompiler::staticTypeOf(const Expr& object) {
  PouSym* owner = pou_.kind == PouKind::FunctionBlock || pou_.kind == PouKind::Program ? &pou_ : pou_.owner;
  if (object.kind == ExprKind::Deref && object.lhs &&
      (object.lhs->kind == ExprKind::This || object.lhs->kind == ExprKind::Super)) {
    if (!owner) return kNoType;
    if (object.lhs->kind == ExprKind::Super) return owner->base ? owner->base->instanceType : kNoType;
    return owner->instanceType;
  }
  // Paths to an instance (`devs[i]`, `cell.station`, `pDev^`, `GVL.dev`), typed without code.
  if (object.kind == ExprKind::Index && object.lhs) {
    TypeId t = staticTypeOf(*object.lhs);
    return t != kNoType && types()[t].kind == bc::TypeKind::Array ? types()[t].element : kNoType;
  }
  if (object.kind == ExprKind::Deref && object.lhs) {
    TypeId t = staticTypeOf(*object.lhs);
    return t != kNoType && types()[t].kind == bc::TypeKind::Pointer ? types()[t].element : kNoType;
  }
  if (object.kind == ExprKind::Member && object.lhs) return staticMemberType(object);
  if (object.kind != ExprKind::Name) return kNoType;
  std::string n = upper(object.text);
  if (auto it = pou_.localIndex.find(n); it != pou_.localIndex.end()) return pou_.locals[it->second].type;
  if (owner)
    if (auto it = owner->memberIndex.find(n); it != owner->memberIndex.end()) return owner->members[it->second].type;
  if (auto g = model().globalIndex.find(n); g != model().globalIndex.end()) return model().globals[g->second].var.type;
  return kNoType;
}

TypeId PouCompiler::staticMemberType(const Expr& member) {
  std::string key = upper(member.text);
  TypeId t = staticTypeOf(*member.lhs);
  if (t == kNoType && member.lhs->kind == ExprKind::Name) {  // GVL.x, PROGRAM.x
    std::string base = upper(member.lhs->text);
    if (auto g = model().globalIndex.find(base + "." + key); g != model().globalIndex.end())
      return model().globals[g->second].var.type;
    for (const auto& inst : model().programInstances)
      if (upper(inst.name) == base) t = inst.pou->instanceType;
  }
  if (t != kNoType && types()[t].kind == bc::TypeKind::Reference) t = types()[t].element;
  if (t == kNoType || types()[t].kind != bc::TypeKind::Struct) return kNoType;
  for (const auto& f : types()[t].fields)
    if (upper(f.name) == key) return f.type;
  return kNoType;
}

bool PouCompiler::receiverOf(const Expr& object, Receiver& recv) {
  if (object.kind == ExprKind::Deref && object.lhs &&
      (object.lhs->kind == ExprKind::This || object.lhs->kind == ExprKind::Super)) {
    PouSym* owner = pou_.kind == PouKind::FunctionBlock ? &pou_ : pou_.owner;
    if (!owner || owner->kind != PouKind::FunctionBlock) return false;
    recv.thisReg = kThis;
    recv.staticClass = object.lhs->kind == ExprKind::Super ? owner->base : owner;
    recv.exact = object.lhs->kind == ExprKind::Super;
    return recv.staticClass != nullptr;
  }
  // Interface-typed variables hold the address of an instance.
  if (object.kind == ExprKind::Name || object.kind == ExprKind::Member || object.kind == ExprKind::Index) {
    auto p = place(object, false);
    if (!p) return false;
    if (auto itf = model().interfaceByType.find(p->type); itf != model().interfaceByType.end()) {
      Place slot = *p;
      recv.thisReg = load(slot);
      recv.viaInterface = itf->second;
      return true;
    }
    auto fb = model().fbByType.find(p->type);
    if (fb == model().fbByType.end()) return false;
    recv.thisReg = addressOf(*p);
    recv.staticClass = fb->second;
    // A REFERENCE TO or VAR_IN_OUT of an FB type may stand for a derived instance: dispatch on
    // its class id. A variable, member or element holds exactly its declared FB.
    recv.exact = !p->viaReference && !(p->var && p->var->byReference);
    return true;
  }
  if (object.kind == ExprKind::Deref) {
    auto p = place(object, false);
    if (!p) return false;
    auto fb = model().fbByType.find(p->type);
    if (fb == model().fbByType.end()) return false;
    recv.thisReg = addressOf(*p);
    recv.staticClass = fb->second;
    return true;
  }
  return false;
}

bool PouCompiler::hasProperty(TypeId type, const std::string& upperName) {
  if (auto fb = model().fbByType.find(type); fb != model().fbByType.end()) return fb->second->properties.count(upperName);
  if (auto itf = model().interfaceByType.find(type); itf != model().interfaceByType.end())
    return itf->second->properties.count(upperName);
  return false;
}

std::optional<Value> PouCompiler::memberProperty(const Expr& e) {
  // Quick structural check before generating any code for the object.
  const Expr& object = *e.lhs;
  std::string key = upper(e.text);
  if (!hasProperty(staticTypeOf(object), key)) return std::nullopt;
  Receiver recv;
  if (!receiverOf(object, recv)) return std::nullopt;
  const PropertySym& prop = recv.viaInterface ? recv.viaInterface->properties[key] : recv.staticClass->properties[key];
  return propertyGet(prop, recv, e.loc);
}

bool PouCompiler::propertySet(const Expr& target, const Expr& valueExpr, SourceLocation loc) {
  std::string key;
  Receiver recv;
  PouSym* owner = pou_.kind == PouKind::FunctionBlock || pou_.kind == PouKind::Program ? &pou_ : pou_.owner;
  if (target.kind == ExprKind::Name) {
    key = upper(target.text);
    if (pou_.localIndex.count(key) || !owner || !owner->properties.count(key)) return false;
    if (owner->memberIndex.count(key)) return false;
    recv.thisReg = kThis;
    recv.staticClass = owner;
  } else if (target.kind == ExprKind::Member) {
    key = upper(target.text);
    const Expr& object = *target.lhs;
    if (!hasProperty(staticTypeOf(object), key) || !receiverOf(object, recv)) return false;
  } else {
    return false;
  }
  auto targets = dispatchTargets(recv, key, true, true);
  if (targets.empty()) {
    diags().error(diag::E209, loc, "property '" + key + "' has no SET accessor");
    return true;
  }
  PouSym& proto = *targets.front().second;
  const VarInfo* in = nullptr;
  for (const auto& l : proto.locals)
    if (upper(l.name) == key) in = &l;
  if (!in) return true;
  Value v = expr(valueExpr, in->type);
  if (v.ok() && types().isScalar(in->type)) v = coerce(v, in->type, loc);
  if (!v.ok()) return true;
  emitDispatch(*this, recv, targets, [&](PouSym& setter) {
    pou_.callees.push_back(&setter);
    uint16_t inner = regMark();
    uint16_t frame = emitFrameCall(setter, recv.thisReg);
    const VarInfo* slotVar = nullptr;
    for (const auto& l : setter.locals)
      if (upper(l.name) == key) slotVar = &l;
    if (slotVar) assignValue(frameSlot(*slotVar, frame), v, loc);
    emitBx(Op::CALL, frame, setter.bcIndex);
    freeRegs(inner);
  });
  return true;
}

// `Standard.CONCAT(...)`, `Tc2_Standard.LEFT(...)`: a standard function or a function of the
// built-in library under its library's namespace (a user's FUNCTION is in no library).
Value PouCompiler::libraryCall(const std::string& upperName, const Expr& e, TypeId expected) {
  if (auto b = builtin(upperName, e, expected)) return *b;
  if (auto fn = model().pouByName.find(upperName); fn != model().pouByName.end() && fn->second->isLibrary &&
                                                   fn->second->kind == PouKind::Function)
    return callFunction(*fn->second, e);
  diags().error(diag::E201, e.lhs->loc, "'" + e.lhs->lhs->text + "." + e.lhs->text +
                                            "' is not a function of the standard library; standard functions and "
                                            "library FBs may be qualified, a program's own FUNCTIONs may not");
  return Value::error();
}

Value PouCompiler::call(const Expr& e, TypeId expected) {
  const Expr& callee = *e.lhs;
  if (callee.kind == ExprKind::Name) {
    std::string key = upper(callee.text);
    if (pou_.kind == PouKind::Function && key == upper(pou_.name)) {
      diags().error(diag::E207, callee.loc, "FUNCTION '" + pou_.name + "' calls itself; IEC 61131-3 does not allow recursion");
      return Value::error();
    }
    // a variable of FB type
    auto p = namePlace(callee, false);
    if (p) {
      if (auto fb = model().fbByType.find(p->type); fb != model().fbByType.end()) return callFbInstance(*p, *fb->second, e);
      diags().error(diag::E206, callee.loc, "'" + callee.text + "' is a variable of type " + describe(types(), p->type) +
                                                 ", not a function block instance");
      return Value::error();
    }
    // CODESYS lets any POU call a PROGRAM like an FB instance: PRG(in := 1, out => x).
    for (const auto& inst : model().programInstances)
      if (upper(inst.name) == key) {
        Place self;
        self.type = inst.pou->instanceType;
        self.offset = inst.address;
        return callFbInstance(self, *inst.pou, e);
      }
    PouSym* owner = pou_.kind == PouKind::FunctionBlock || pou_.kind == PouKind::Program ? &pou_ : pou_.owner;
    if (owner) {
      if (owner->methods.count(key)) {
        Receiver recv;
        recv.thisReg = kThis;
        recv.staticClass = owner;
        return callMethod(callee.text, recv, e);
      }
      if (auto a = owner->actions.find(key); a != owner->actions.end()) return callAction(*a->second, kThis);
    }
    if (auto b = builtin(key, e, expected)) return *b;
    auto fn = model().pouByName.find(key);
    if (fn != model().pouByName.end()) {
      if (fn->second->kind == PouKind::Function) return callFunction(*fn->second, e);
      diags().error(diag::E206, callee.loc, "'" + callee.text + "' is a " +
                                                 (fn->second->kind == PouKind::Program ? "PROGRAM" : "FUNCTION_BLOCK") +
                                                 " type; call an instance of it instead");
      return Value::error();
    }
    diags().error(diag::E201, callee.loc, "'" + callee.text + "' is not declared (no such function, function block instance, method or action)");
    return Value::error();
  }
  if (callee.kind == ExprKind::Member) {
    std::string key = upper(callee.text);
    if (callee.lhs->kind == ExprKind::Name && isLibraryNamespace(upper(callee.lhs->text)) && !namePlace(*callee.lhs, false))
      return libraryCall(key, e, expected);
    // program action: MAIN.Act()
    if (callee.lhs->kind == ExprKind::Name)
      for (const auto& inst : model().programInstances)
        if (upper(inst.name) == upper(callee.lhs->text))
          if (auto a = inst.pou->actions.find(key); a != inst.pou->actions.end())
            return callAction(*a->second, loadConstInt(inst.address));
    Receiver recv;
    bool isMethodCall = false;
    // Decide by the object's static type whether this is a method/action or a nested FB instance.
    {
      const Expr& object = *callee.lhs;
      TypeId objectType = staticTypeOf(object);
      if (objectType != kNoType && types().isReference(objectType) && !model().interfaceByType.count(objectType))
        objectType = types()[objectType].element;
      if (auto fb = model().fbByType.find(objectType); fb != model().fbByType.end())
        isMethodCall = fb->second->methods.count(key) || fb->second->actions.count(key);
      if (auto itf = model().interfaceByType.find(objectType); itf != model().interfaceByType.end())
        isMethodCall = itf->second->methods.count(key) > 0;
      if (objectType == kNoType && object.kind != ExprKind::Name) isMethodCall = true;
    }
    if (isMethodCall && receiverOf(*callee.lhs, recv)) {
      if (recv.staticClass)
        if (auto a = recv.staticClass->actions.find(key); a != recv.staticClass->actions.end())
          return callAction(*a->second, recv.thisReg);
      bool known = recv.viaInterface ? recv.viaInterface->methods.count(key) : recv.staticClass->methods.count(key);
      if (!known) {
        diags().error(diag::E212, callee.loc, "no METHOD '" + callee.text + "' in " +
                                                  (recv.viaInterface ? recv.viaInterface->name : recv.staticClass->name));
        return Value::error();
      }
      return callMethod(callee.text, recv, e);
    }
    auto p = place(callee, false);
    if (!p) return Value::error();
    if (auto fb = model().fbByType.find(p->type); fb != model().fbByType.end()) return callFbInstance(*p, *fb->second, e);
    diags().error(diag::E206, callee.loc, "'" + callee.text + "' cannot be called");
    return Value::error();
  }
  if (callee.kind == ExprKind::Deref || callee.kind == ExprKind::Index) {
    auto p = place(callee, false);
    if (!p) return Value::error();
    if (callee.kind == ExprKind::Deref && callee.lhs && callee.lhs->kind == ExprKind::Super) {
      // SUPER^(): run the base FB's body on this instance
      auto fb = model().fbByType.find(p->type);
      if (fb != model().fbByType.end()) return callFbInstance(*p, *fb->second, e);
    }
    if (auto fb = model().fbByType.find(p->type); fb != model().fbByType.end()) return callFbInstance(*p, *fb->second, e);
    diags().error(diag::E206, callee.loc, "this expression cannot be called");
    return Value::error();
  }
  diags().error(diag::E206, callee.loc, "this expression cannot be called");
  return Value::error();
}

}  // namespace virtcom::st
