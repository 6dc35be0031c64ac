// Code generation: statements and the body of one POU.
#include <algorithm>

#include "lang/st/codegen/check.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/codegen/init_program.hpp"
#include "lang/st/codegen/peephole.hpp"

namespace virtcom::st {

using bc::Op;

static bool declaredIn(const Pou& ast, const VarDecl& decl) {
  for (const auto& block : ast.varBlocks)
    for (const auto& d : block.vars)
      if (&d == &decl) return true;
  return false;
}

void PouCompiler::compile() {
  codeStart_ = here();
  const size_t firstLine = ctx_.module.lines.size();
  tempTop_ = 0;
  tempMax_ = 0;
  const bool hasBody = pou_.ast->hasBody || !pou_.ast->body.empty();
  if (hasBody) {
    const StmtList frameInits = buildFrameInitCalls(model(), types(), pou_);
    statements(frameInits);
    edgeInputs();
    covering_ = coversPou();
    collectLabels(pou_.ast->body);
    statements(pou_.ast->body);
    covering_ = false;
  }
  uint32_t end = here();
  for (uint32_t r : returns_) patchJump(r, end);
  if (hasBody) statements(buildFrameExitCalls(model(), types(), pou_));
  emit(Op::RET, 0, 0, 0);
  if (!diags().hasErrors()) maxReg_ = optimizePou(ctx_.module, codeStart_, firstLine, maxReg_);
  bc::PouInfo& info = ctx_.module.pous[pou_.bcIndex];
  info.codeStart = codeStart_;
  info.codeSize = here() - codeStart_;
  info.numRegs = maxReg_;
  pou_.frameSize = (pou_.frameSize + tempMax_ + 7) / 8 * 8;
  info.frameSize = pou_.frameSize;
}

// The implicit R_TRIG/F_TRIG of each R_EDGE/F_EDGE input this POU declares (IEC 61131-3),
// before the body: edge := input rose (fell) since the last call; previous := input. On BOOLs
// (0/1) a rise is previous < input, a fall input < previous. A derived FB's body does not
// repeat it: the base body (SUPER^()) owns its inputs' edges.
void PouCompiler::edgeInputs() {
  if (pou_.kind != PouKind::FunctionBlock && pou_.kind != PouKind::Program) return;
  for (const VarInfo& input : pou_.members) {
    if (input.edge == EdgeKind::None || !input.decl || !declaredIn(*pou_.ast, *input.decl)) continue;
    const uint16_t mark = regMark();
    const uint16_t now = load(varPlace(input, kThis));
    const Place edge = varPlace(pou_.members[input.edgeMember], kThis);
    const Place previous = varPlace(pou_.members[input.edgeMember + 1], kThis);
    const uint16_t before = load(previous);
    const uint16_t result = allocReg();
    if (input.edge == EdgeKind::Rising)
      emit(Op::LT_U, result, before, now);
    else
      emit(Op::LT_U, result, now, before);
    store(edge, result);
    store(previous, now);
    freeRegs(mark);
  }
}

// Each statement of a list starts its registers where the previous one's ended, wrapping back
// to the list's first register after kRotatingRegisters, instead of reusing the same ones: what
// the previous statements loaded or computed then stays in registers, and load forwarding
// (load_forwarding.hpp) serves the next statements' loads from them. Registers below the
// list's first (held by the enclosing statements) are never reused.
void PouCompiler::statements(const StmtList& list) {
  constexpr uint16_t kRotatingRegisters = 32;
  const bool labelled = openLabelScope(list);
  const uint16_t first = regMark();
  const uint16_t enclosingTop = regTop_;
  uint16_t top = first;
  for (const auto& s : list) {
    regTop_ = regMark();
    statement(*s);
    top = std::max(top, regTop_);
    freeRegs(regTop_ - first >= kRotatingRegisters ? first : regTop_);
  }
  freeRegs(first);
  regTop_ = std::max(enclosingTop, top);
  if (labelled) closeLabelScope();
}

// An activity-diagram rule's IF with nothing in its THEN is there for its coverage probe alone.
static bool onlyForCoverage(const Stmt& s) {
  return s.cover == CoverRole::RuleFired && std::all_of(s.branches.begin(), s.branches.end(), [](const CondBlock& b) {
           return b.body.empty();
         });
}

void PouCompiler::statement(const Stmt& s) {
  if (!covering_ && onlyForCoverage(s)) return;
  uint16_t mark = regMark();
  uint32_t tempMark = tempTop_;
  if (s.kind != StmtKind::Empty && s.kind != StmtKind::Label) ctx_.module.lines.push_back({here(), s.loc});
  if (covering_) coverStatement(s);
  switch (s.kind) {
    case StmtKind::Assign:
    case StmtKind::SetAssign:
    case StmtKind::ResetAssign:
    case StmtKind::RefAssign: assignment(s); break;
    case StmtKind::AttemptAssign: attemptAssignment(s); break;
    case StmtKind::Call: {
      if (s.expr && s.expr->kind == ExprKind::Call) {
        (void)call(*s.expr, kNoType);
      } else if (s.expr) {
        diags().error(diag::E206, s.loc, "this expression is not a statement; did you mean ':=' or a call?");
      }
      break;
    }
    case StmtKind::If: ifStatement(s); break;
    case StmtKind::Case: caseStatement(s); break;
    case StmtKind::For: forStatement(s); break;
    case StmtKind::While: whileStatement(s); break;
    case StmtKind::Repeat: repeatStatement(s); break;
    case StmtKind::Exit:
    case StmtKind::Continue: jumpOut(s); break;
    case StmtKind::Return: returns_.push_back(emitJump(Op::JMP, 0)); break;
    case StmtKind::Jump: jump(s); break;
    case StmtKind::Label: placeLabel(s); break;
    case StmtKind::Empty: break;
  }
  freeRegs(mark);
  tempTop_ = tempMark;
}

void PouCompiler::assignment(const Stmt& s) {
  if (s.kind == StmtKind::Assign && propertySet(*s.lhs, *s.rhs, s.loc)) return;
  auto target = place(*s.lhs, true);
  if (!target) {
    (void)expr(*s.rhs);  // still report errors on the right-hand side
    return;
  }
  if (!checkAssignable(diags(), *target, pou_, s.lhs->loc)) return;
  if (s.kind == StmtKind::RefAssign) {
    if (!target->viaReference) {
      diags().error(diag::E209, s.lhs->loc, "REF= needs a REFERENCE TO variable on the left");
      return;
    }
    auto src = place(*s.rhs, false);
    if (!src) return;
    if (!sameOrDerivedFb(model(), src->type, target->type)) {
      diags().error(diag::E202, s.rhs->loc, "REF= binds a REFERENCE TO " + describe(types(), target->type) + " to a " +
                                                describe(types(), src->type));
      return;
    }
    store(referenceSlot(*target), addressOf(*src));  // the reference itself, not the referee
    return;
  }
  if (s.kind == StmtKind::SetAssign || s.kind == StmtKind::ResetAssign) {
    uint16_t c = condition(*s.rhs);
    uint32_t skip = emitJump(Op::JZ, c);
    Value bit = constInt(TypeTable::elem(ElemType::Bool), s.kind == StmtKind::SetAssign ? 1 : 0);
    if (!storeConst(*target, bit)) store(*target, toReg(bit));
    patchJump(skip, here());
    return;
  }
  assign(*target, *s.rhs, s.rhs->loc);
}

uint16_t PouCompiler::condition(const Expr& e) {
  Value v = expr(e, TypeTable::elem(ElemType::Bool));
  if (!v.ok()) return allocReg();
  if (!types().isBool(v.type)) {
    diags().error(diag::E202, e.loc, "a condition must be BOOL, found " + describe(types(), v.type));
    return allocReg();
  }
  return toReg(v);
}

// With coverage each arm starts with its probe; without ELSE the implicit one gets a probe too,
// reached only when no condition held (the last arm then jumps over it).
void PouCompiler::ifStatement(const Stmt& s) {
  const uint16_t arms = probedArms(s, s.branches.size());
  std::vector<uint32_t> toEnd;
  uint16_t arm = 0;
  for (const auto& branch : s.branches) {
    uint16_t mark = regMark();
    uint16_t c = condition(*branch.cond);
    uint32_t skip = emitJump(Op::JZ, c);
    freeRegs(mark);
    if (arms) probe(CoverageKind::Branch, s.loc, arm++, arms);
    if (covering_ && s.cover == CoverRole::RuleFired) probe(CoverageKind::Rule, s.coverLoc, 0, 0, s.coverName);
    statements(branch.body);
    if (&branch != &s.branches.back() || s.hasElse || arms) toEnd.push_back(emitJump(Op::JMP, 0));
    patchJump(skip, here());
  }
  if (arms) probe(CoverageKind::Branch, s.loc, arm, arms);
  if (s.hasElse) statements(s.elseBody);
  for (uint32_t j : toEnd) patchJump(j, here());
}

void PouCompiler::caseStatement(const Stmt& s) {
  Value sel = expr(*s.expr);
  if (!sel.ok()) return;
  TypeTable& t = types();
  if (!t.isInteger(sel.type) && !t.isEnum(sel.type)) {
    diags().error(diag::E202, s.expr->loc, "CASE needs an integer or enumeration selector, found " + describe(t, sel.type));
    return;
  }
  uint16_t r = toReg(sel);
  std::vector<CaseLabelRange> seen;
  auto labelValue = [&](const Expr& e) -> std::optional<int64_t> {
    Value v = expr(e, sel.type);
    if (!v.ok()) return std::nullopt;
    if (v.kind != Value::Kind::Const) {
      diags().error(diag::E101, e.loc, "a CASE label must be a constant");
      return std::nullopt;
    }
    if (t.isEnum(sel.type) && v.type != sel.type) {
      diags().error(diag::E202, e.loc, "CASE label of type " + describe(t, v.type) + " for a selector of type " + describe(t, sel.type));
      return std::nullopt;
    }
    return v.c.i;
  };
  const uint16_t arms = probedArms(s, s.cases.size());
  uint16_t arm = 0;
  std::vector<uint32_t> toEnd;
  for (const auto& branch : s.cases) {
    // One label: jump over the body unless it matches; several: jump into the body if any matches.
    const bool single = branch.labels.size() == 1;
    std::vector<uint32_t> toBody, toNext;
    for (const auto& label : branch.labels) {
      uint16_t mark = regMark();
      auto lo = labelValue(*label.lo);
      auto hi = label.hi ? labelValue(*label.hi) : lo;
      if (!lo || !hi) continue;
      checkCaseLabel(diags(), t, sel.type, {*lo, *hi, label.lo->loc}, label.hi != nullptr, seen);
      uint16_t c = allocReg();
      auto compareWith = [&](Op op, Op opK, uint16_t into, int64_t k, bool constFirst) {
        if (k >= INT16_MIN && k <= INT16_MAX) emit(opK, into, r, static_cast<uint16_t>(k));
        else if (constFirst) emit(op, into, loadConstInt(k), r);
        else emit(op, into, r, loadConstInt(k));
      };
      if (*lo == *hi) {
        compareWith(Op::EQ, Op::EQK, c, *lo, false);
      } else {
        uint16_t c2 = allocReg();
        compareWith(Op::LE_I, Op::GEK, c, *lo, true);
        compareWith(Op::LE_I, Op::LEK, c2, *hi, false);
        emit(Op::BAND, c, c, c2);
      }
      (single ? toNext : toBody).push_back(emitJump(single ? Op::JZ : Op::JNZ, c));
      freeRegs(mark);
    }
    if (!single) toNext.push_back(emitJump(Op::JMP, 0));
    for (uint32_t j : toBody) patchJump(j, here());
    if (arms) probe(CoverageKind::Branch, s.loc, arm++, arms);
    if (covering_ && s.cover == CoverRole::RuleFired) probe(CoverageKind::Rule, s.coverLoc, 0, 0, s.coverName);
    statements(branch.body);
    if (&branch != &s.cases.back() || s.hasElse || arms) toEnd.push_back(emitJump(Op::JMP, 0));
    for (uint32_t j : toNext) patchJump(j, here());
  }
  if (arms) probe(CoverageKind::Branch, s.loc, arm, arms);
  if (s.hasElse) statements(s.elseBody);
  for (uint32_t j : toEnd) patchJump(j, here());
}

void PouCompiler::forStatement(const Stmt& s) {
  auto var = place(*s.lhs, true);
  if (!var) return;
  if (!checkForVariable(diags(), types(), *var, s.lhs->loc)) return;
  TypeTable& t = types();
  assign(*var, *s.rhs, s.rhs->loc);
  Value endV = coerce(expr(*s.to, var->type), var->type, s.to->loc);
  if (!endV.ok()) return;
  uint16_t end = allocReg();
  emit(Op::MOV, end, toReg(endV), 0);
  int64_t stepConst = 1;
  uint16_t step = 0xffff;
  if (s.by) {
    Value by = coerce(expr(*s.by, var->type), var->type, s.by->loc);
    if (!by.ok()) return;
    if (by.kind == Value::Kind::Const) {
      stepConst = by.c.i;
      if (stepConst == 0) diags().warning(diag::W302, s.by->loc, "FOR with BY 0 never ends");
    } else {
      step = allocReg();
      emit(Op::MOV, step, toReg(by), 0);
    }
  }
  bool uns = !t.isSignedInt(var->type);
  Op le = uns ? Op::LE_U : Op::LE_I;
  // c := the loop goes on with the control variable's value in register i.
  const auto goesOn = [&](uint16_t i) {
    uint16_t c = allocReg();
    if (step == 0xffff) {
      if (stepConst >= 0) emit(le, c, i, end);
      else emit(le, c, end, i);
    } else {
      // the direction is known only at run time
      uint16_t zero = loadConstInt(0), neg = allocReg();
      emit(Op::LT_I, neg, step, zero);
      uint32_t down = emitJump(Op::JNZ, neg);
      emit(le, c, i, end);
      uint32_t joined = emitJump(Op::JMP, 0);
      patchJump(down, here());
      emit(le, c, end, i);
      patchJump(joined, here());
    }
    return c;
  };
  // The test comes first and again after each step, so an iteration costs the step and one
  // test. The control variable's register stays allocated through the body and is loaded into
  // the same register at the top and after the step: the load forwarding pass
  // (load_forwarding.hpp) then serves the body's reads of the variable from it.
  uint16_t mark = regMark();
  uint16_t i = load(*var);
  uint16_t held = regMark();
  uint32_t exit = emitJump(Op::JZ, goesOn(i));
  freeRegs(held);
  uint32_t body = here();
  loops_.push_back({});
  statements(s.body);
  uint32_t cont = here();
  freeRegs(mark);
  uint16_t i2 = load(*var);
  if (step == 0xffff && stepConst >= INT16_MIN && stepConst <= INT16_MAX) {
    emit(Op::ADDI, i2, i2, static_cast<uint16_t>(static_cast<int16_t>(stepConst)));
  } else if (step == 0xffff) {
    uint16_t k = loadConstInt(stepConst);
    emit(Op::ADD, i2, i2, k);
  } else {
    emit(Op::ADD, i2, i2, step);
  }
  store(*var, i2);
  freeRegs(mark);
  jumpTo(Op::JNZ, goesOn(load(*var)), body);
  freeRegs(mark);
  uint32_t after = here();
  patchJump(exit, after);
  for (uint32_t b : loops_.back().breaks) patchJump(b, after);
  for (uint32_t k : loops_.back().continues) patchJump(k, cont);
  loops_.pop_back();
}

void PouCompiler::whileStatement(const Stmt& s) {
  uint32_t top = here();
  uint16_t mark = regMark();
  uint16_t c = condition(*s.expr);
  uint32_t exit = emitJump(Op::JZ, c);
  freeRegs(mark);
  loops_.push_back({});
  statements(s.body);
  jumpTo(Op::JMP, 0, top);
  uint32_t after = here();
  patchJump(exit, after);
  for (uint32_t b : loops_.back().breaks) patchJump(b, after);
  for (uint32_t k : loops_.back().continues) patchJump(k, top);
  loops_.pop_back();
}

void PouCompiler::repeatStatement(const Stmt& s) {
  uint32_t top = here();
  loops_.push_back({});
  statements(s.body);
  uint32_t cont = here();
  uint16_t mark = regMark();
  uint16_t c = condition(*s.expr);
  jumpTo(Op::JZ, c, top);
  freeRegs(mark);
  uint32_t after = here();
  for (uint32_t b : loops_.back().breaks) patchJump(b, after);
  for (uint32_t k : loops_.back().continues) patchJump(k, cont);
  loops_.pop_back();
}

void PouCompiler::jumpOut(const Stmt& s) {
  if (loops_.empty()) {
    diags().error(diag::E211, s.loc, std::string(s.kind == StmtKind::Exit ? "EXIT" : "CONTINUE") + " is only allowed inside FOR, WHILE or REPEAT");
    return;
  }
  uint32_t j = emitJump(Op::JMP, 0);
  if (s.kind == StmtKind::Exit) loops_.back().breaks.push_back(j);
  else loops_.back().continues.push_back(j);
}

}  // namespace virtcom::st
