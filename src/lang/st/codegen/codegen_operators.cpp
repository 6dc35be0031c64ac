// Code generation: the CODESYS operators on references and interfaces, __ISVALIDREF,
// __QUERYINTERFACE and __QUERYPOINTER, lowered to loads, compares and jumps.
#include "lang/st/codegen/check.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

using bc::Op;

std::optional<Value> PouCompiler::codesysOperator(const std::string& upperName, const Expr& e) {
  if (upperName == "__ISVALIDREF") return isValidRef(e);
  if (upperName == "__QUERYINTERFACE") return queryInterface(e);
  if (upperName == "__QUERYPOINTER") return queryPointer(e);
  // The memory functions of TwinCAT's Tc2_System and CODESYS's MemUtils, unless the program
  // brings its own POU of that name.
  if ((upperName == "MEMCPY" || upperName == "MEMMOVE" || upperName == "MEMSET" || upperName == "MEMCMP") &&
      !model().pouByName.count(upperName))
    return memoryFunction(upperName, e);
  return std::nullopt;
}

// MEMCPY/MEMMOVE(dest, src, n) and MEMSET(dest, byte, n) return dest (UDINT); MEMCMP(a, b, n)
// returns -1, 0 or 1 (DINT). Addresses are POINTERs (ADR(x)) or integers of at least 32 bits.
// A range outside the PLC's memory is an invalid pointer fault, never a write elsewhere.
Value PouCompiler::memoryFunction(const std::string& name, const Expr& e) {
  auto operands = operatorOperands(e, 3);
  if (!operands) return Value::error();
  const bool fill = name == "MEMSET";
  std::vector<uint16_t> regs;
  for (size_t i = 0; i < 3; ++i) {
    const Expr& operand = *(*operands)[i];
    Value v = expr(operand, TypeTable::elem(ElemType::Udint));
    if (!v.ok()) return Value::error();
    bool address = i == 0 || (i == 1 && !fill);
    bool fits = types().isInteger(v.type) && (!address || v.kind == Value::Kind::Const || types().bits(v.type) >= 32);
    if (!fits && !(address && types().isPointer(v.type))) {
      diags().error(diag::E202, operand.loc, name + (address ? " needs an address (ADR(x), a POINTER or a UDINT/LWORD)"
                                                            : " needs an integer") + ", found " + describe(types(), v.type));
      return Value::error();
    }
    regs.push_back(types().isPointer(v.type) ? toReg(v) : toReg(convert(v, TypeTable::elem(ElemType::Lword), operand.loc)));
  }
  if (name == "MEMCMP") return callNative(bc::Native::MEM_CMP, regs, TypeTable::elem(ElemType::Dint));
  return callNative(fill ? bc::Native::MEM_SET : bc::Native::MEM_COPY, regs, TypeTable::elem(ElemType::Udint));
}

// The operators take `count` positional operands; nullopt (with E203) otherwise.
std::optional<std::vector<const Expr*>> PouCompiler::operatorOperands(const Expr& e, size_t count) {
  const std::string& name = e.lhs->text;
  bool positional = true;
  for (const auto& a : e.args) positional = positional && a.name.empty() && !a.output && a.value;
  if (e.args.size() != count) {
    diags().error(diag::E203, e.loc, name + " takes " + std::to_string(count) + " operand(s), found " +
                                         std::to_string(e.args.size()));
    return std::nullopt;
  }
  if (!positional) {
    diags().error(diag::E203, e.loc, name + " takes its operands by position, without names");
    return std::nullopt;
  }
  std::vector<const Expr*> out;
  for (const auto& a : e.args) out.push_back(a.value.get());
  return out;
}

Value PouCompiler::isValidRef(const Expr& e) {
  auto operands = operatorOperands(e, 1);
  if (!operands) return Value::error();
  const Expr& operand = *operands->front();
  auto p = place(operand, false);
  if (!p) return Value::error();
  // place() stands for the referee, whose address is the reference's value.
  if (!p->viaReference && !(p->var && p->var->byReference)) {
    diags().error(diag::E202, operand.loc, "__ISVALIDREF needs a REFERENCE TO or VAR_IN_OUT variable, found " +
                                               describe(types(), p->type) + "; test an interface or POINTER with <> 0");
    return Value::error();
  }
  // An unbound reference holds 0; no variable lives below the null guard.
  uint16_t result = allocReg();
  emit(Op::GEK, result, addressOf(*p), static_cast<uint16_t>(bc::Module::kNullGuard));
  return regValue(TypeTable::elem(ElemType::Bool), result);
}

std::optional<PouCompiler::InstanceOperand> PouCompiler::instanceOperand(const Expr& operand, const std::string& op) {
  auto p = place(operand, false);
  if (!p) return std::nullopt;
  if (model().interfaceByType.count(p->type)) return InstanceOperand{load(*p), nullptr};
  if (auto fb = model().fbByType.find(p->type); fb != model().fbByType.end() && fb->second->kind == PouKind::FunctionBlock)
    return InstanceOperand{addressOf(*p), fb->second};
  diags().error(diag::E202, operand.loc, op + " needs an interface or a function block instance first, found " +
                                             describe(types(), p->type));
  return std::nullopt;
}

Value PouCompiler::queryInterface(const Expr& e) {
  auto operands = operatorOperands(e, 2);
  if (!operands) return Value::error();
  auto source = instanceOperand(*(*operands)[0], "__QUERYINTERFACE");
  auto dest = place(*(*operands)[1], true);
  if (!source || !dest) return Value::error();
  auto itf = model().interfaceByType.find(dest->type);
  if (itf == model().interfaceByType.end()) {
    diags().error(diag::E202, (*operands)[1]->loc, "__QUERYINTERFACE needs an interface variable second, found " +
                                                       describe(types(), dest->type));
    return Value::error();
  }
  // The classes whose instances the destination may hold. An FB without a class header
  // implements no interface (and its first bytes are no class id).
  std::vector<uint32_t> classIds;
  if (!source->fb || source->fb->hasClassHeader)
    for (const PouSym* c : model().classes)
      if (!c->isAbstract && implementsInterface(model(), c, upper(itf->second->name))) classIds.push_back(c->classId);
  // As in CODESYS the destination is set to 0 when the instance does not implement it.
  auto [found, instance] = classTest(source->address, classIds);
  store(*dest, instance);
  return regValue(TypeTable::elem(ElemType::Bool), found);
}

std::pair<uint16_t, uint16_t> PouCompiler::classTest(uint16_t address, const std::vector<uint32_t>& classIds) {
  uint16_t found = loadConstInt(0);
  uint16_t instance = loadConstInt(0);
  if (!classIds.empty()) {
    uint32_t isNull = emitJump(Op::JZ, address);
    uint16_t cls = allocReg();
    emit(Op::LD_U32, cls, address, 0);
    for (uint32_t id : classIds) {
      uint16_t same = allocReg();
      emit(Op::EQ, same, cls, loadConstInt(id));
      emit(Op::BOR, found, found, same);
    }
    uint32_t notFound = emitJump(Op::JZ, found);
    emit(Op::MOV, instance, address, 0);
    patchJump(isNull, here());
    patchJump(notFound, here());
  }
  return {found, instance};
}

// `dest ?= source` (IEC 61131-3 ed. 3 assignment attempt). dest is an interface, a REF_TO
// (POINTER TO) or a REFERENCE TO a function block; source an interface, an FB instance or a REF_TO/POINTER TO an
// FB. dest gets the instance when its class (the dynamic one, read from the class header) is
// dest's FB or derives from it, or implements dest's interface; NULL otherwise.
void PouCompiler::attemptAssignment(const Stmt& s) {
  auto dest = place(*s.lhs, true);
  if (!dest) return;
  if (!checkAssignable(diags(), *dest, pou_, s.lhs->loc)) return;
  const InterfaceSym* itf = nullptr;
  const PouSym* fb = nullptr;
  auto functionBlock = [&](TypeId type) -> const PouSym* {
    auto f = model().fbByType.find(type);
    return f != model().fbByType.end() && f->second->kind == PouKind::FunctionBlock ? f->second : nullptr;
  };
  if (auto i = model().interfaceByType.find(dest->type); i != model().interfaceByType.end()) itf = i->second;
  if (types().isPointer(dest->type)) {
    fb = functionBlock(types()[dest->type].element);
  } else if (dest->viaReference && (fb = functionBlock(dest->type))) {
    // A REFERENCE TO an FB: the attempt binds the reference itself (unbound when it fails).
    dest = referenceSlot(*dest);
  }
  if (!itf && !fb) {
    diags().error(diag::E202, s.lhs->loc, "?= needs an interface, a REF_TO or a REFERENCE TO a function block on the left, found " +
                                              describe(types(), dest->type));
    return;
  }
  auto source = attemptSource(*s.rhs);
  if (!source) return;
  auto fits = [&](const PouSym* c) { return itf ? implementsInterface(model(), c, upper(itf->name)) : derivesFrom(c, fb); };
  std::vector<uint32_t> classIds;
  if (source->fb && !source->fb->hasClassHeader) {
    // No class header: the instance is exactly of its declared FB, decided here.
    if (fits(source->fb)) {
      store(*dest, source->address);
      return;
    }
  } else {
    for (const PouSym* c : model().classes)
      if (!c->isAbstract && fits(c)) classIds.push_back(c->classId);
  }
  store(*dest, classTest(source->address, classIds).second);
}

// The right side of ?=: an instance address and its declared FB (null behind an interface).
std::optional<PouCompiler::InstanceOperand> PouCompiler::attemptSource(const Expr& operand) {
  auto p = place(operand, false);
  if (!p) return std::nullopt;
  if (types().isPointer(p->type))
    if (auto f = model().fbByType.find(types()[p->type].element); f != model().fbByType.end() &&
                                                                 f->second->kind == PouKind::FunctionBlock)
      return InstanceOperand{load(*p), f->second->hasClassHeader ? nullptr : f->second};
  if (model().interfaceByType.count(p->type)) return InstanceOperand{load(*p), nullptr};
  if (auto f = model().fbByType.find(p->type); f != model().fbByType.end() && f->second->kind == PouKind::FunctionBlock)
    return InstanceOperand{addressOf(*p), f->second};
  diags().error(diag::E202, operand.loc, "?= needs an interface, a function block instance or a REF_TO a function block "
                                         "on the right, found " + describe(types(), p->type));
  return std::nullopt;
}

Value PouCompiler::queryPointer(const Expr& e) {
  auto operands = operatorOperands(e, 2);
  if (!operands) return Value::error();
  auto source = instanceOperand(*(*operands)[0], "__QUERYPOINTER");
  auto dest = place(*(*operands)[1], true);
  if (!source || !dest) return Value::error();
  if (!types().isPointer(dest->type)) {
    diags().error(diag::E202, (*operands)[1]->loc, "__QUERYPOINTER needs a POINTER variable second, found " +
                                                       describe(types(), dest->type));
    return Value::error();
  }
  // Like CODESYS the pointer is untyped: it may be a POINTER TO any FB, PVOID or BYTE.
  store(*dest, source->address);
  uint16_t valid = allocReg();
  emit(Op::NEK, valid, source->address, 0);
  return regValue(TypeTable::elem(ElemType::Bool), valid);
}

}  // namespace virtcom::st
