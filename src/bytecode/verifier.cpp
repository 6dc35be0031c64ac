#include "bytecode/verifier.hpp"

#include <algorithm>

namespace virtcom::bc {

namespace {
using O = Operand;
using W = WideOperand;
constexpr OperandRoles abc3(O a, O b, O c) { return {a, b, c, W::None, 0}; }
constexpr OperandRoles wide(O a, W bx, uint8_t width = 0) { return {a, O::None, O::None, bx, width}; }
constexpr OperandRoles kRRR = abc3(O::Reg, O::Reg, O::Reg);
constexpr OperandRoles kRR = abc3(O::Reg, O::Reg, O::None);
constexpr OperandRoles kRRImm = abc3(O::Reg, O::Reg, O::Imm);
constexpr OperandRoles kRRSImm = abc3(O::Reg, O::Reg, O::SImm);
}  // namespace

// A switch without default: a new opcode without roles is a -Wswitch warning.
OperandRoles operandRoles(Op op) {
  switch (op) {
    case Op::NOP: case Op::RET: return {};
    case Op::MOV: return kRR;
    case Op::LDI: return wide(O::Reg, W::SImm);
    case Op::LDK: return wide(O::Reg, W::Const);
    case Op::SYSTIME: return abc3(O::Reg, O::None, O::None);
    case Op::LD_I8: case Op::LD_U8: case Op::LD_I16: case Op::LD_U16: case Op::LD_I32:
    case Op::LD_U32: case Op::LD_64: case Op::LD_F32:
    case Op::ST_8: case Op::ST_16: case Op::ST_32: case Op::ST_64: case Op::ST_F32: return kRRImm;
    case Op::STK_8: case Op::STK_16: case Op::STK_32: case Op::STK_64: return abc3(O::SImm, O::Reg, O::Imm);
    case Op::LD_BIT: case Op::ST_BIT: return abc3(O::Reg, O::Reg, O::BitIndex);
    case Op::LDA_I8: case Op::LDA_U8: case Op::STA_8: return wide(O::Reg, W::Abs, 1);
    case Op::LDA_I16: case Op::LDA_U16: case Op::STA_16: return wide(O::Reg, W::Abs, 2);
    case Op::LDA_I32: case Op::LDA_U32: case Op::LDA_F32: case Op::STA_32: case Op::STA_F32:
      return wide(O::Reg, W::Abs, 4);
    case Op::LDA_64: case Op::STA_64: return wide(O::Reg, W::Abs, 8);
    case Op::COPY: return kRRR;
    case Op::INDEX: return abc3(O::Reg, O::Reg, O::Index);
    case Op::ADD: case Op::SUB: case Op::MUL: case Op::DIV_I: case Op::MOD_I: case Op::DIV_U:
    case Op::MOD_U: return kRRR;
    case Op::ADDI: return kRRSImm;
    case Op::DIVK: case Op::MODK: return abc3(O::Reg, O::Reg, O::Divisor);
    case Op::NEG: return kRR;
    case Op::SEXT: case Op::ZEXT: return abc3(O::Reg, O::Reg, O::BitCount);
    case Op::BAND: case Op::BOR: case Op::BXOR: return kRRR;
    case Op::BNOT: case Op::LNOT: return kRR;
    case Op::SHL: case Op::SHR: return kRRR;
    case Op::EQ: case Op::NE: case Op::LT_I: case Op::LE_I: case Op::LT_U: case Op::LE_U:
    case Op::EQ_F: case Op::NE_F: case Op::LT_F: case Op::LE_F: return kRRR;
    case Op::EQK: case Op::NEK: case Op::LTK: case Op::LEK: case Op::GTK: case Op::GEK: return kRRSImm;
    case Op::ADD_F: case Op::SUB_F: case Op::MUL_F: case Op::DIV_F: case Op::ADD_F32:
    case Op::SUB_F32: case Op::MUL_F32: case Op::DIV_F32: return kRRR;
    case Op::NEG_F: case Op::RND_F32: return kRR;
    case Op::I2F: case Op::U2F: case Op::F2I: case Op::F2I_TRUNC: case Op::F2U: return kRR;
    case Op::JMP: return wide(O::None, W::Jump);
    case Op::JZ: case Op::JNZ: return wide(O::Reg, W::Jump);
    case Op::JEQ: case Op::JNE: case Op::JLT_I: case Op::JLE_I: case Op::JLT_U: case Op::JLE_U:
      return abc3(O::Reg, O::Reg, O::Branch);
    case Op::JEQK: case Op::JNEK: case Op::JLTK: case Op::JLEK: case Op::JGTK: case Op::JGEK:
      return abc3(O::Reg, O::Branch, O::SImm);
    case Op::ENTER: case Op::CALL: return wide(O::Reg, W::Pou);
    case Op::CALLN: return wide(O::Reg, W::Native);
    case Op::CALLFB: return wide(O::Reg, W::NativeFb);
    case Op::TRAP: return wide(O::None, W::Fault);
    case Op::COVER: return wide(O::None, W::Counter, 8);
    case Op::Count_: break;
  }
  return {};
}

bool writesOnlyA(Op op) {
  switch (op) {
    case Op::ST_8: case Op::ST_16: case Op::ST_32: case Op::ST_64: case Op::ST_F32: case Op::ST_BIT:
    case Op::STA_8: case Op::STA_16: case Op::STA_32: case Op::STA_64: case Op::STA_F32:
    case Op::COPY: case Op::CALL: case Op::CALLN: case Op::CALLFB: return false;
    default: return operandRoles(op).a == Operand::Reg && !isBranch(op);
  }
}

namespace {

class Verifier {
 public:
  explicit Verifier(const Module& m) : m_(m) {}

  std::string run() {
    if (!layout() || !pous() || !lines() || !types() || !names()) return error_;
    for (uint32_t i = 0; i < m_.pous.size(); ++i)
      if (!code(i)) return error_;
    return {};
  }

 private:
  bool fail(std::string msg) {
    error_ = std::move(msg);
    return false;
  }
  bool failAt(uint32_t pou, uint32_t pc, const std::string& msg) {
    return fail("pou '" + m_.pous[pou].name + "' pc " + std::to_string(pc) + ": " + msg);
  }
  // [address, address + size) inside [kNullGuard, staticSize) (or empty).
  bool inStatic(uint64_t address, uint64_t size) const {
    if (size == 0) return address <= m_.staticSize;
    return address >= Module::kNullGuard && address + size <= m_.staticSize;
  }

  bool layout() {
    if (m_.writableEnd > m_.staticSize)
      return fail("writableEnd " + std::to_string(m_.writableEnd) + " is beyond the static image");
    if (m_.initialImage.size() != m_.staticSize)
      return fail("initial image has " + std::to_string(m_.initialImage.size()) + " bytes, static size is " +
                  std::to_string(m_.staticSize));
    if (m_.staticSize < Module::kNullGuard) return fail("static size below the null guard");
    if (uint64_t{m_.staticSize} + m_.stackSize > 0xffffffffu) return fail("memory larger than 4 GiB");
    if (m_.registerStackSize < 2) return fail("register stack smaller than 2");
    for (const ProcessArea* a : {&m_.inputs, &m_.outputs, &m_.memory})
      if (a->size && !inStatic(a->address, a->size)) return fail("process image area outside static memory");
    if (m_.initPou != Module::kNoPou && m_.initPou >= m_.pous.size()) return fail("init pou index out of range");
    if (m_.exitPou != Module::kNoPou && m_.exitPou >= m_.pous.size()) return fail("exit pou index out of range");
    const CoverageTable& cov = m_.coverage;
    if (!cov.probes.empty() && !inStatic(cov.counterAddress, uint64_t{8} * cov.probes.size()))
      return fail("coverage counters outside static memory");
    for (const CoverageProbe& p : cov.probes)
      if (p.pou >= m_.pous.size()) return fail("coverage probe of pou index " + std::to_string(p.pou) + " out of range");
    return true;
  }

  bool pous() {
    for (const PouInfo& p : m_.pous) {
      const std::string where = "pou '" + p.name + "': ";
      if (p.codeSize == 0) return fail(where + "no code");
      if (uint64_t{p.codeStart} + p.codeSize > m_.code.size()) return fail(where + "code range outside the code");
      if (p.numRegs < 2) return fail(where + "fewer than 2 registers");
      if (p.numRegs > m_.registerStackSize) return fail(where + "register window larger than the register stack");
      if (p.frameSize && !inStatic(p.frameTemplate, p.frameSize))
        return fail(where + "frame template outside static memory");
      if (p.frameSize > m_.stackSize) return fail(where + "frame larger than the stack");
      if (p.instanceType != kNoType && p.instanceType >= m_.types.size())
        return fail(where + "instance type out of range");
      const Op last = m_.code[p.codeStart + p.codeSize - 1].op;
      if (last != Op::RET && last != Op::JMP && last != Op::TRAP)
        return fail(where + "code does not end with RET, JMP or TRAP");
    }
    return true;
  }

  bool lines() {
    for (size_t i = 0; i < m_.lines.size(); ++i) {
      const LineEntry& e = m_.lines[i];
      if (e.pc >= m_.code.size()) return fail("line entry " + std::to_string(i) + " outside the code");
      if (i && e.pc < m_.lines[i - 1].pc) return fail("line table not sorted by pc");
      if (e.loc.line && e.loc.fileId >= m_.files.size())
        return fail("line entry " + std::to_string(i) + " names unknown file " + std::to_string(e.loc.fileId));
    }
    return true;
  }

  bool validType(TypeId t) const { return t < m_.types.size(); }

  bool types() {
    for (TypeId id = 0; id < m_.types.size(); ++id) {
      const TypeDesc& t = m_.types[id];
      const std::string where = "type " + std::to_string(id) + " '" + t.name + "': ";
      switch (t.kind) {
        case TypeKind::Elementary: {
          const uint32_t size = elemTypeInfo(t.elem).sizeBytes;
          if (size && t.size != size) return fail(where + "size does not match its elementary type");
          break;
        }
        case TypeKind::String: {
          const uint64_t unit = t.elem == ElemType::Wstring ? 2 : 1;
          if (t.size < unit * (uint64_t{t.stringLength} + 1)) return fail(where + "too small for its length");
          break;
        }
        case TypeKind::Array: {
          if (!validType(t.element)) return fail(where + "element type out of range");
          if (t.dims.empty()) return fail(where + "no dimensions");
          uint64_t count = 1;
          for (const ArrayDim& d : t.dims) {
            if (d.hi < d.lo) return fail(where + "empty dimension");
            count *= d.count();
            if (count > 0xffffffffu) return fail(where + "too many elements");
          }
          if (count * m_.types[t.element].size > t.size) return fail(where + "smaller than its elements");
          break;
        }
        case TypeKind::Struct:
          for (const Field& f : t.fields) {
            if (!validType(f.type)) return fail(where + "field '" + f.name + "' has an invalid type");
            const uint64_t size = f.bit >= 0 ? (f.bit / 8) + 1 : m_.types[f.type].size;
            if (f.absolute ? !inStatic(f.offset, size) : uint64_t{f.offset} + size > t.size)
              return fail(where + "field '" + f.name + "' outside the " + (f.absolute ? "static memory" : "struct"));
          }
          break;
        case TypeKind::Enum:
          if (!isInteger(t.elem) || t.size != elemTypeInfo(t.elem).sizeBytes)
            return fail(where + "enum base is not an integer of its size");
          break;
        case TypeKind::Pointer:
        case TypeKind::Reference:
          if (t.element != kNoType && !validType(t.element)) return fail(where + "target type out of range");
          if (t.size != 4 && t.size != 8) return fail(where + "pointer size is not 4 or 8");
          break;
      }
    }
    return true;
  }

  bool names() {
    for (const Symbol& s : m_.symbols) {
      if (!validType(s.type)) return fail("symbol '" + s.name + "' has an invalid type");
      if (!inStatic(s.address, std::max<uint32_t>(m_.types[s.type].size, 1)))
        return fail("symbol '" + s.name + "' outside static memory");
    }
    for (const ProgramInstance& p : m_.programs) {
      if (p.pou >= m_.pous.size()) return fail("program '" + p.name + "' has an invalid pou");
      const TypeId t = m_.pous[p.pou].instanceType;
      if (validType(t) && !inStatic(p.address, std::max<uint32_t>(m_.types[t].size, 1)))
        return fail("program '" + p.name + "' instance outside static memory");
    }
    for (const TaskInfo& t : m_.tasks)
      for (uint32_t p : t.programs)
        if (p >= m_.programs.size()) return fail("task '" + t.name + "' names an invalid program");
    return true;
  }

  bool regOk(uint32_t pou, uint32_t pc, uint64_t reg, uint64_t count = 1) {
    const uint32_t window = m_.pous[pou].numRegs;
    if (reg + count <= window) return true;
    return failAt(pou, pc, "register " + std::to_string(reg + count - 1) + " outside window of " + std::to_string(window));
  }

  bool targetOk(uint32_t pou, uint32_t pc, int64_t target) {
    const PouInfo& p = m_.pous[pou];
    if (target >= p.codeStart && target < int64_t{p.codeStart} + p.codeSize) return true;
    return failAt(pou, pc, "jump target " + std::to_string(target) + " outside the pou");
  }

  bool smallOk(uint32_t pou, uint32_t pc, Operand role, uint16_t v) {
    switch (role) {
      case Operand::Reg: return regOk(pou, pc, v);
      case Operand::BitIndex: return v < 8 || failAt(pou, pc, "bit index " + std::to_string(v) + " above 7");
      case Operand::BitCount:
        return (v >= 1 && v <= 64) || failAt(pou, pc, "bit count " + std::to_string(v) + " not in 1..64");
      case Operand::Divisor: return v != 0 || failAt(pou, pc, "divisor 0");
      case Operand::Index:
        return v < m_.indexes.size() || failAt(pou, pc, "index descriptor " + std::to_string(v) + " out of range");
      case Operand::Branch: return targetOk(pou, pc, int64_t{pc} + 1 + static_cast<int16_t>(v));
      default: return true;
    }
  }

  bool wideOk(uint32_t pou, uint32_t pc, const Instr& ins, const OperandRoles& roles) {
    const uint32_t bx = ins.bx();
    switch (roles.bx) {
      case W::Const:
        return bx < m_.constants.size() || failAt(pou, pc, "constant " + std::to_string(bx) + " out of range");
      case W::Abs:
        return inStatic(bx, roles.width) ||
               failAt(pou, pc, "absolute address " + std::to_string(bx) + " outside static memory");
      case W::Pou:
        if (bx >= m_.pous.size()) return failAt(pou, pc, "pou index " + std::to_string(bx) + " out of range");
        return ins.op != Op::CALL || regOk(pou, pc, ins.a, 2);
      case W::Native: {
        if (bx >= static_cast<uint32_t>(Native::Count_))
          return failAt(pou, pc, "native index " + std::to_string(bx) + " out of range");
        return regOk(pou, pc, ins.a, std::max(1u, nativeArity(static_cast<Native>(bx))));
      }
      case W::NativeFb:
        return bx < static_cast<uint32_t>(NativeFb::Count_) ||
               failAt(pou, pc, "native FB index " + std::to_string(bx) + " out of range");
      case W::Jump: return targetOk(pou, pc, branchTarget(pc, ins));
      case W::Counter:
        return m_.coverage.counterAt(bx) < m_.coverage.probes.size() ||
               failAt(pou, pc, "address " + std::to_string(bx) + " is no coverage counter");
      case W::Fault:
        return (bx >= 1 && bx <= static_cast<uint32_t>(FaultKind::SubrangeViolation)) ||
               failAt(pou, pc, "trap kind " + std::to_string(bx) + " unknown");
      default: return true;
    }
  }

  bool code(uint32_t pou) {
    const PouInfo& p = m_.pous[pou];
    for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
      const Instr& ins = m_.code[pc];
      if (static_cast<uint32_t>(ins.op) >= static_cast<uint32_t>(Op::Count_))
        return failAt(pou, pc, "invalid opcode " + std::to_string(static_cast<unsigned>(ins.op)));
      const OperandRoles roles = operandRoles(ins.op);
      if (!smallOk(pou, pc, roles.a, ins.a)) return false;
      if (opFormat(ins.op) == Format::ABC) {
        if (!smallOk(pou, pc, roles.b, ins.b) || !smallOk(pou, pc, roles.c, ins.c)) return false;
      } else if (!wideOk(pou, pc, ins, roles)) {
        return false;
      }
    }
    return true;
  }

  const Module& m_;
  std::string error_;
};

}  // namespace

std::string verifyModule(const Module& m) { return Verifier(m).run(); }

}  // namespace virtcom::bc
