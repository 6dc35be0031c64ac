#include "vm/machine.hpp"

#include <algorithm>
#include <cstring>

#include "vm/natives.hpp"
#include "vm/value.hpp"

// The dispatch loop compiles as computed goto with GCC/Clang (one indirect jump per opcode,
// generated from opcodes.def) and as a plain switch elsewhere.
#if defined(__GNUC__) && !defined(VIRTCOM_VM_SWITCH_DISPATCH)
#define VIRTCOM_VM_COMPUTED_GOTO 1
#else
#define VIRTCOM_VM_COMPUTED_GOTO 0
#endif

namespace virtcom::vm {

using bc::FaultKind;
using bc::Instr;
using bc::Module;
using bc::Op;

Machine::Machine(const bc::Module& m)
    : m_(m),
      memory_(m.memorySize(), 0),
      scratch_(m.memorySize() + 1, 0),
      regs_(std::max<uint32_t>(m.registerStackSize, 2), 0),
      frames_(m.maxCallDepth) {
  fault_.callStack.reserve(m.maxCallDepth);
  sp_ = m.staticSize;
}

bool Machine::coldStart() {
  std::fill(memory_.begin(), memory_.end(), 0);
  size_t n = std::min<size_t>({m_.initialImage.size(), m_.staticSize, memory_.size()});
  std::memcpy(memory_.data(), m_.initialImage.data(), n);
  sp_ = m_.staticSize;
  fault_ = FaultInfo{};
  fault_.callStack.reserve(m_.maxCallDepth);
  if (m_.initPou == Module::kNoPou) return true;
  return run(m_.initPou, 0);
}

bool Machine::raise(FaultKind kind, uint32_t pc, uint32_t depth, uint32_t startSp) {
  fault_.kind = kind;
  fault_.pc = pc;
  fault_.loc = m_.locationOf(pc);
  fault_.callStack.clear();
  for (uint32_t i = depth; i-- > 0;) fault_.callStack.push_back(frames_[i].returnPc - 1);
  sp_ = startSp;
  return false;
}

bool Machine::run(uint32_t pou, uint32_t thisAddress) {
  const uint32_t startSp = sp_;
  if (pou >= m_.pous.size()) return raise(FaultKind::InvalidPointer, 0, 0, startSp);
  const bc::PouInfo& p = m_.pous[pou];
  if (p.numRegs > regs_.size() || uint64_t{sp_} + p.frameSize > memory_.size())
    return raise(FaultKind::StackOverflow, p.codeStart, 0, startSp);
  std::memcpy(memory_.data() + sp_, m_.initialImage.data() + p.frameTemplate, p.frameSize);
  regs_[0] = sp_;
  regs_[1] = thisAddress;
  sp_ += p.frameSize;
  return execute(p.codeStart, startSp);
}

// The interpreter. Invariants from the verifier: pc stays inside code (every POU ends with an
// unconditional transfer), register operands are inside the window, constant/POU/native
// indices and absolute addresses are valid. Everything computed at run time is checked here.
#if VIRTCOM_VM_COMPUTED_GOTO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"  // labels as values
#endif
bool Machine::execute(uint32_t pc, const uint32_t startSp) {
  const Instr* const code = m_.code.data();
  const bc::PouInfo* const pous = m_.pous.data();
  const uint64_t* const constants = m_.constants.data();
  const uint8_t* const image = m_.initialImage.data();
  uint8_t* const mem = memory_.data();
  const uint64_t memSize = memory_.size();
  const uint64_t guard = Module::kNullGuard;
  const uint64_t regCount = regs_.size();
  const uint32_t maxDepth = static_cast<uint32_t>(frames_.size());
  const uint32_t staticSize = m_.staticSize;
  const NativeContext nctx{mem, static_cast<uint32_t>(memSize), Module::kNullGuard, scratch_.data()};
  uint64_t* const regs = regs_.data();
  uint32_t base = 0;
  uint64_t* r = regs;
  uint32_t depth = 0;
  uint64_t sp = sp_;
  uint64_t remaining = budget_;
  uint64_t executed = 0;
  Instr ins;
  uint64_t ad = 0;

#define VM_FAULT(kind)                                    \
  do {                                                    \
    executed_ += executed;                                \
    return raise(FaultKind::kind, pc - 1, depth, startSp); \
  } while (0)
#define VM_ADDR(width) \
  if (!checkedAddress(r[ins.b], ins.c, width, memSize, guard, ad)) VM_FAULT(InvalidPointer)
#define VM_LOAD(T, expr)                     \
  VM_ADDR(sizeof(T));                        \
  {                                          \
    T v = loadLe<T>(mem + ad);               \
    r[ins.a] = (expr);                       \
  }                                          \
  VM_NEXT()
#define VM_STORE(T, expr)        \
  VM_ADDR(sizeof(T));            \
  storeLe<T>(mem + ad, (expr));  \
  VM_NEXT()
#define VM_LOADA(T, expr)                \
  {                                      \
    T v = loadLe<T>(mem + ins.bx());     \
    r[ins.a] = (expr);                   \
  }                                      \
  VM_NEXT()
#define VM_STOREA(T, expr) storeLe<T>(mem + ins.bx(), (expr)); VM_NEXT()
#define VM_BIN(expr) { const uint64_t x = r[ins.b], y = r[ins.c]; r[ins.a] = (expr); } VM_NEXT()
#define VM_BINF(expr) { const double x = asF(r[ins.b]), y = asF(r[ins.c]); r[ins.a] = (expr); } VM_NEXT()
#define VM_BACKWARD_CHECK(offset) \
  if ((offset) < 0) {             \
    if (remaining == 0) VM_FAULT(WatchdogBudget); \
    --remaining;                  \
  }

#if VIRTCOM_VM_COMPUTED_GOTO
  static void* const kLabels[] = {
#define X(name, fmt, meaning) &&op_##name,
#include "bytecode/opcodes.def"
#undef X
  };
#define VM_NEXT()                                  \
  do {                                             \
    ins = code[pc++];                              \
    ++executed;                                    \
    goto* kLabels[static_cast<uint8_t>(ins.op)];   \
  } while (0)
#define VM_CASE(name) op_##name:
  VM_NEXT();
#else
#define VM_NEXT() continue
#define VM_CASE(name) case Op::name:
  for (;;) {
    ins = code[pc++];
    ++executed;
    switch (ins.op) {
#endif

  VM_CASE(NOP) VM_NEXT();
  VM_CASE(MOV) r[ins.a] = r[ins.b]; VM_NEXT();
  VM_CASE(LDI) r[ins.a] = fromI(ins.sbx()); VM_NEXT();
  VM_CASE(LDK) r[ins.a] = constants[ins.bx()]; VM_NEXT();
  VM_CASE(SYSTIME) r[ins.a] = fromI(taskTimeNs_); ++timeReads_; VM_NEXT();

  VM_CASE(LD_I8) VM_LOAD(int8_t, fromI(v));
  VM_CASE(LD_U8) VM_LOAD(uint8_t, uint64_t{v});
  VM_CASE(LD_I16) VM_LOAD(int16_t, fromI(v));
  VM_CASE(LD_U16) VM_LOAD(uint16_t, uint64_t{v});
  VM_CASE(LD_I32) VM_LOAD(int32_t, fromI(v));
  VM_CASE(LD_U32) VM_LOAD(uint32_t, uint64_t{v});
  VM_CASE(LD_64) VM_LOAD(uint64_t, v);
  VM_CASE(LD_F32) VM_LOAD(float, fromF(static_cast<double>(v)));
  VM_CASE(LD_BIT)
    if (!checkedAddress(r[ins.b], 0, 1, memSize, guard, ad)) VM_FAULT(InvalidPointer);
    r[ins.a] = (mem[ad] >> (ins.c & 7u)) & 1u;
    VM_NEXT();

  VM_CASE(ST_8) VM_STORE(uint8_t, static_cast<uint8_t>(r[ins.a]));
  VM_CASE(ST_16) VM_STORE(uint16_t, static_cast<uint16_t>(r[ins.a]));
  VM_CASE(ST_32) VM_STORE(uint32_t, static_cast<uint32_t>(r[ins.a]));
  VM_CASE(ST_64) VM_STORE(uint64_t, r[ins.a]);
  VM_CASE(ST_F32) VM_STORE(float, static_cast<float>(asF(r[ins.a])));
  VM_CASE(ST_BIT)
    if (!checkedAddress(r[ins.b], 0, 1, memSize, guard, ad)) VM_FAULT(InvalidPointer);
    {
      const uint8_t mask = static_cast<uint8_t>(1u << (ins.c & 7u));
      mem[ad] = r[ins.a] != 0 ? (mem[ad] | mask) : (mem[ad] & ~mask);
    }
    VM_NEXT();

  VM_CASE(LDA_I8) VM_LOADA(int8_t, fromI(v));
  VM_CASE(LDA_U8) VM_LOADA(uint8_t, uint64_t{v});
  VM_CASE(LDA_I16) VM_LOADA(int16_t, fromI(v));
  VM_CASE(LDA_U16) VM_LOADA(uint16_t, uint64_t{v});
  VM_CASE(LDA_I32) VM_LOADA(int32_t, fromI(v));
  VM_CASE(LDA_U32) VM_LOADA(uint32_t, uint64_t{v});
  VM_CASE(LDA_64) VM_LOADA(uint64_t, v);
  VM_CASE(LDA_F32) VM_LOADA(float, fromF(static_cast<double>(v)));
  VM_CASE(STA_8) VM_STOREA(uint8_t, static_cast<uint8_t>(r[ins.a]));
  VM_CASE(STA_16) VM_STOREA(uint16_t, static_cast<uint16_t>(r[ins.a]));
  VM_CASE(STA_32) VM_STOREA(uint32_t, static_cast<uint32_t>(r[ins.a]));
  VM_CASE(STA_64) VM_STOREA(uint64_t, r[ins.a]);
  VM_CASE(STA_F32) VM_STOREA(float, static_cast<float>(asF(r[ins.a])));

  VM_CASE(COPY) {
    const uint64_t n = r[ins.c];
    uint64_t src = 0;
    if (!checkedAddress(r[ins.a], 0, n, memSize, guard, ad) ||
        !checkedAddress(r[ins.b], 0, n, memSize, guard, src))
      VM_FAULT(InvalidPointer);
    std::memmove(mem + ad, mem + src, n);
  }
    VM_NEXT();
  VM_CASE(BOUND)
    if (asI(r[ins.a]) < 0 || r[ins.a] >= ins.bx()) VM_FAULT(IndexOutOfRange);
    VM_NEXT();

  VM_CASE(ADD) VM_BIN(x + y);
  VM_CASE(SUB) VM_BIN(x - y);
  VM_CASE(MUL) VM_BIN(x * y);
  VM_CASE(DIV_I)
    if (r[ins.c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(asI(y) == -1 ? 0 - x : fromI(asI(x) / asI(y)));
  VM_CASE(MOD_I)
    if (r[ins.c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(asI(y) == -1 ? 0 : fromI(asI(x) % asI(y)));
  VM_CASE(DIV_U)
    if (r[ins.c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(x / y);
  VM_CASE(MOD_U)
    if (r[ins.c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(x % y);
  VM_CASE(ADDI) r[ins.a] = r[ins.b] + fromI(static_cast<int16_t>(ins.c)); VM_NEXT();
  VM_CASE(MULI) r[ins.a] = r[ins.b] * uint64_t{ins.c}; VM_NEXT();
  VM_CASE(NEG) r[ins.a] = 0 - r[ins.b]; VM_NEXT();
  VM_CASE(SEXT) {
    const unsigned bits = ins.c;
    const uint64_t v = r[ins.b];
    r[ins.a] = bits == 0 ? 0 : bits >= 64 ? v : fromI(asI(v << (64 - bits)) >> (64 - bits));
  }
    VM_NEXT();
  VM_CASE(ZEXT) {
    const unsigned bits = ins.c;
    const uint64_t v = r[ins.b];
    r[ins.a] = bits >= 64 ? v : v & ((uint64_t{1} << bits) - 1);
  }
    VM_NEXT();
  VM_CASE(BAND) VM_BIN(x & y);
  VM_CASE(BOR) VM_BIN(x | y);
  VM_CASE(BXOR) VM_BIN(x ^ y);
  VM_CASE(BNOT) r[ins.a] = ~r[ins.b]; VM_NEXT();
  VM_CASE(LNOT) r[ins.a] = r[ins.b] == 0; VM_NEXT();
  VM_CASE(SHL) VM_BIN(y < 64 ? x << y : 0);
  VM_CASE(SHR) VM_BIN(y < 64 ? x >> y : 0);

  VM_CASE(EQ) VM_BIN(x == y);
  VM_CASE(NE) VM_BIN(x != y);
  VM_CASE(LT_I) VM_BIN(asI(x) < asI(y));
  VM_CASE(LE_I) VM_BIN(asI(x) <= asI(y));
  VM_CASE(LT_U) VM_BIN(x < y);
  VM_CASE(LE_U) VM_BIN(x <= y);
  VM_CASE(EQ_F) VM_BINF(x == y);
  VM_CASE(NE_F) VM_BINF(x != y);
  VM_CASE(LT_F) VM_BINF(x < y);
  VM_CASE(LE_F) VM_BINF(x <= y);

  VM_CASE(ADD_F) VM_BINF(fromF(x + y));
  VM_CASE(SUB_F) VM_BINF(fromF(x - y));
  VM_CASE(MUL_F) VM_BINF(fromF(x * y));
  VM_CASE(DIV_F) VM_BINF(fromF(x / y));
  VM_CASE(ADD_F32) VM_BINF(fromF(static_cast<float>(x + y)));
  VM_CASE(SUB_F32) VM_BINF(fromF(static_cast<float>(x - y)));
  VM_CASE(MUL_F32) VM_BINF(fromF(static_cast<float>(x * y)));
  VM_CASE(DIV_F32) VM_BINF(fromF(static_cast<float>(x / y)));
  VM_CASE(NEG_F) r[ins.a] = fromF(-asF(r[ins.b])); VM_NEXT();
  VM_CASE(RND_F32) r[ins.a] = fromF(static_cast<float>(asF(r[ins.b]))); VM_NEXT();

  VM_CASE(I2F) r[ins.a] = fromF(static_cast<double>(asI(r[ins.b]))); VM_NEXT();
  VM_CASE(U2F) r[ins.a] = fromF(static_cast<double>(r[ins.b])); VM_NEXT();
  VM_CASE(F2I) r[ins.a] = fromI(roundToI64(asF(r[ins.b]))); VM_NEXT();
  VM_CASE(F2I_TRUNC) r[ins.a] = fromI(truncToI64(asF(r[ins.b]))); VM_NEXT();
  VM_CASE(F2U) r[ins.a] = roundToU64(asF(r[ins.b])); VM_NEXT();

  VM_CASE(JMP)
    VM_BACKWARD_CHECK(ins.sbx());
    pc += static_cast<uint32_t>(ins.sbx());
    VM_NEXT();
  VM_CASE(JZ)
    if (r[ins.a] == 0) {
      VM_BACKWARD_CHECK(ins.sbx());
      pc += static_cast<uint32_t>(ins.sbx());
    }
    VM_NEXT();
  VM_CASE(JNZ)
    if (r[ins.a] != 0) {
      VM_BACKWARD_CHECK(ins.sbx());
      pc += static_cast<uint32_t>(ins.sbx());
    }
    VM_NEXT();
  VM_CASE(ENTER) {
    const bc::PouInfo& p = pous[ins.bx()];
    if (sp + p.frameSize > memSize) VM_FAULT(StackOverflow);
    std::memcpy(mem + sp, image + p.frameTemplate, p.frameSize);
    r[ins.a] = sp;
    sp += p.frameSize;
  }
    VM_NEXT();
  VM_CASE(CALL) {
    const bc::PouInfo& p = pous[ins.bx()];
    if (remaining == 0) VM_FAULT(WatchdogBudget);
    --remaining;
    const uint64_t newBase = uint64_t{base} + ins.a;
    if (depth >= maxDepth || newBase + p.numRegs > regCount) VM_FAULT(StackOverflow);
    frames_[depth++] = CallFrame{pc, base, r[ins.a]};
    base = static_cast<uint32_t>(newBase);
    r = regs + base;
    pc = p.codeStart;
  }
    VM_NEXT();
  VM_CASE(CALLN) {
    const FaultKind k = kNatives[ins.bx()](r + ins.a, nctx);
    if (k != FaultKind::None) {
      executed_ += executed;
      return raise(k, pc - 1, depth, startSp);
    }
  }
    VM_NEXT();
  VM_CASE(RET)
    if (depth == 0) {
      sp_ = startSp;
      executed_ += executed;
      return true;
    }
    {
      const CallFrame& f = frames_[--depth];
      // sp = the callee's fp, unless the bytecode never allocated one (fp not on the stack).
      if (f.fp >= staticSize && f.fp <= sp) sp = f.fp;
      base = f.base;
      r = regs + base;
      pc = f.returnPc;
    }
    VM_NEXT();
  VM_CASE(TRAP) {
    const uint32_t kind = ins.bx();
    executed_ += executed;
    return raise(kind <= static_cast<uint32_t>(FaultKind::SubrangeViolation) && kind != 0
                     ? static_cast<FaultKind>(kind)
                     : FaultKind::InvalidEnumValue,
                 pc - 1, depth, startSp);
  }

#if !VIRTCOM_VM_COMPUTED_GOTO
      case Op::Count_: break;
    }
    executed_ += executed;
    return raise(FaultKind::InvalidPointer, pc - 1, depth, startSp);  // unreachable after verification
  }
#endif
#undef VM_FAULT
#undef VM_ADDR
#undef VM_LOAD
#undef VM_STORE
#undef VM_LOADA
#undef VM_STOREA
#undef VM_BIN
#undef VM_BINF
#undef VM_BACKWARD_CHECK
#undef VM_NEXT
#undef VM_CASE
}
#if VIRTCOM_VM_COMPUTED_GOTO
#pragma GCC diagnostic pop
#endif

std::string FaultInfo::describe(const bc::Module& m) const {
  auto where = [&m](uint32_t pc, SourceLocation loc) {
    std::string s;
    if (loc.line != 0) {
      s = loc.fileId < m.files.size() ? m.files[loc.fileId] : "<unknown>";
      s += ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col);
    } else {
      s = "pc " + std::to_string(pc);
    }
    return s;
  };
  auto pouName = [&m](uint32_t pc) {
    uint32_t p = m.pouAt(pc);
    return p == bc::Module::kNoPou ? std::string("?") : m.pous[p].name;
  };
  std::string out = std::string(bc::faultText(kind)) + " at " + where(pc, loc);
  if (loc.line == 0) out += " (in " + pouName(pc) + ")";
  for (uint32_t site : callStack)
    out += "\n  called from " + where(site, m.locationOf(site)) + " (in " + pouName(site) + ")";
  return out;
}

}  // namespace virtcom::vm
