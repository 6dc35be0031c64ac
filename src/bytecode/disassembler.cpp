#include "bytecode/disassembler.hpp"

#include <algorithm>
#include <cstdio>

#include "bytecode/verifier.hpp"

namespace virtcom::bc {

namespace {

std::string_view pouKindName(PouKind k) {
  switch (k) {
    case PouKind::Program: return "Program";
    case PouKind::Function: return "Function";
    case PouKind::FunctionBlock: return "FunctionBlock";
    case PouKind::Method: return "Method";
    case PouKind::Action: return "Action";
    case PouKind::PropertyGet: return "PropertyGet";
    case PouKind::PropertySet: return "PropertySet";
    case PouKind::Init: return "Init";
  }
  return "?";
}

std::string pcText(int64_t pc) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%04lld", static_cast<long long>(pc));
  return buf;
}

std::string smallOperand(Operand role, uint16_t v, uint32_t pc) {
  switch (role) {
    case Operand::Branch: return pcText(int64_t{pc} + 1 + static_cast<int16_t>(v));
    case Operand::None: return {};
    case Operand::Reg: return "r" + std::to_string(v);
    case Operand::SImm: return std::to_string(static_cast<int16_t>(v));
    case Operand::Index: return "x" + std::to_string(v);
    default: return std::to_string(v);
  }
}

std::string wideOperand(const Module& m, uint32_t pc, const Instr& ins, WideOperand role) {
  const uint32_t bx = ins.bx();
  switch (role) {
    case WideOperand::None: return {};
    case WideOperand::SImm: return std::to_string(ins.sbx());
    case WideOperand::Imm: return std::to_string(bx);
    case WideOperand::Const: return "k" + std::to_string(bx);
    case WideOperand::Abs: return "@" + std::to_string(bx);
    case WideOperand::Pou: return bx < m.pous.size() ? m.pous[bx].name : "pou#" + std::to_string(bx);
    case WideOperand::Native:
      return bx < static_cast<uint32_t>(Native::Count_) ? std::string(nativeName(static_cast<Native>(bx)))
                                                        : "native#" + std::to_string(bx);
    case WideOperand::NativeFb:
      return bx < static_cast<uint32_t>(NativeFb::Count_) ? std::string(nativeFbName(static_cast<NativeFb>(bx)))
                                                          : "fb#" + std::to_string(bx);
    case WideOperand::Jump: return pcText(branchTarget(pc, ins));
    case WideOperand::Counter: return "#" + std::to_string(m.coverage.counterAt(bx));
    case WideOperand::Fault:
      return std::to_string(bx) + " (" +
             std::string(bx <= static_cast<uint32_t>(FaultKind::SubrangeViolation) ? faultText(static_cast<FaultKind>(bx))
                                                                                 : "unknown fault") +
             ")";
  }
  return {};
}

std::string fileLine(const Module& m, SourceLocation loc) {
  const std::string file = loc.fileId < m.files.size() ? m.files[loc.fileId] : "file#" + std::to_string(loc.fileId);
  return file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col);
}

}  // namespace

std::string disassembleInstruction(const Module& m, uint32_t pc) {
  if (pc >= m.code.size()) return "?";
  const Instr& ins = m.code[pc];
  if (static_cast<uint32_t>(ins.op) >= static_cast<uint32_t>(Op::Count_))
    return "??? " + std::to_string(static_cast<unsigned>(ins.op));
  const OperandRoles roles = operandRoles(ins.op);
  std::string ops;
  auto add = [&ops](const std::string& s) {
    if (s.empty()) return;
    if (!ops.empty()) ops += ", ";
    ops += s;
  };
  add(smallOperand(roles.a, ins.a, pc));
  if (opFormat(ins.op) == Format::ABC) {
    // A jump target reads best last ("JLTK r2, 100, 0012"), wherever the encoding keeps it.
    const bool targetInB = roles.b == Operand::Branch;
    add(smallOperand(targetInB ? roles.c : roles.b, targetInB ? ins.c : ins.b, pc));
    add(smallOperand(targetInB ? roles.b : roles.c, targetInB ? ins.b : ins.c, pc));
  } else {
    add(wideOperand(m, pc, ins, roles.bx));
  }
  std::string out(opName(ins.op));
  if (ops.empty()) return out;
  out.resize(std::max<size_t>(out.size() + 1, 9), ' ');
  return out + ops;
}

std::string disassemble(const Module& m, uint32_t pou) {
  if (pou >= m.pous.size()) return {};
  const PouInfo& p = m.pous[pou];
  std::string out = p.name + " (" + std::string(pouKindName(p.kind)) + ", " + std::to_string(p.numRegs) +
                    " registers, frame " + std::to_string(p.frameSize) + " bytes @" +
                    std::to_string(p.frameTemplate) + ")\n";
  auto line = std::lower_bound(m.lines.begin(), m.lines.end(), p.codeStart,
                               [](const LineEntry& e, uint32_t pc) { return e.pc < pc; });
  const uint64_t end = std::min<uint64_t>(uint64_t{p.codeStart} + p.codeSize, m.code.size());
  for (uint32_t pc = p.codeStart; pc < end; ++pc) {
    std::string text = "  " + pcText(pc) + "  " + disassembleInstruction(m, pc);
    while (line != m.lines.end() && line->pc < pc) ++line;
    if (line != m.lines.end() && line->pc == pc && line->loc.line != 0) {
      text.resize(std::max<size_t>(text.size() + 1, 31), ' ');
      text += "; " + fileLine(m, line->loc);
    }
    out += text + "\n";
  }
  return out;
}

}  // namespace virtcom::bc
