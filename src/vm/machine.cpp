#include "vm/machine.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

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
      frames_(m.maxCallDepth),
      compiledCallStack_(m.maxCallDepth),
      quick_(quicken(m, memory_.size())) {
  fault_.callStack.reserve(m.maxCallDepth);
  sp_ = m.staticSize;
}

bool Machine::coldStart() {
  // Coverage counters outlive a cold start: a run restarted after a power loss goes on counting.
  const auto counters = memory_.begin() + m_.coverage.counterAddress;
  const std::vector<uint8_t> counted(counters, counters + m_.coverage.counterBytes());
  std::fill(memory_.begin(), memory_.end(), 0);
  size_t n = std::min<size_t>({m_.initialImage.size(), m_.staticSize, memory_.size()});
  std::memcpy(memory_.data(), m_.initialImage.data(), n);
  std::copy(counted.begin(), counted.end(), counters);
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
  for (uint32_t i = depth; i-- > 0;) fault_.callStack.push_back(static_cast<uint32_t>(frames_[i].returnIp - frames_[i].code) - 1);
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
  if (compiled_) return executeCompiled(pou, startSp);
  return execute(pou, startSp);
}

bool Machine::executeCompiled(uint32_t pou, uint32_t startSp) {
  const NativeContext nctx{memory_.data(), static_cast<uint32_t>(memory_.size()), Module::kNullGuard, scratch_.data()};
  AotContext c{memory_.data(), m_.initialImage.data(), regs_.data(), compiledCallStack_.data(),
               kNatives,       &nctx,                    regs_.size(),  sp_,
               budget_,        taskTimeNs_,              timeReads_,    static_cast<uint32_t>(frames_.size()),
               0,              0};
  const int kind = compiled_->entries[pou](&c, 0, 0);
  timeReads_ = c.timeReads;
  sp_ = startSp;
  if (kind == 0) return true;
  fault_.kind = static_cast<FaultKind>(kind);
  fault_.pc = c.faultPc;
  fault_.loc = m_.locationOf(c.faultPc);
  fault_.callStack.assign(compiledCallStack_.begin(), compiledCallStack_.begin() + c.callStackSize);
  return false;
}

// The interpreter. Invariants from the verifier: pc stays inside code (every POU ends with an
// unconditional transfer), register operands are inside the window, constant/POU/native
// indices and absolute addresses are valid. Everything computed at run time is checked here.
#if VIRTCOM_VM_COMPUTED_GOTO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"  // labels as values
#endif
bool Machine::execute(uint32_t pou, uint32_t startSp) {
  return countInstructions_ ? interpret<true>(pou, startSp) : interpret<false>(pou, startSp);
}

template <bool kCounting>
bool Machine::interpret(uint32_t pou, const uint32_t startSp) {
  // Two copies of the code with the same pcs: each activation runs the quickened one if its
  // POU's entry check admits its fp and this, else the module's own (vm/quicken.hpp).
  const Instr* const quick = quick_.code.data();
  const Instr* const plain = m_.code.data();
  const PouEntry* const entry = quick_.entry.data();
  const Instr* code = entry[pou].admits(regs_[0], regs_[1]) ? quick : plain;
  const bc::PouInfo* const pous = m_.pous.data();
  const uint64_t* const constants = m_.constants.data();
  const bc::IndexDesc* const indexes = m_.indexes.data();
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
  // ip points past the instruction being executed (`INS`); operands are read where a handler
  // needs them (decoding all three eagerly costs every dispatch several loads).
  const Instr* ip = code + pous[pou].codeStart;
#define INS (ip - 1)
  const auto pcOf = [&code](const Instr* at) { return static_cast<uint32_t>(at - code); };
  // The signed 16-bit immediates of ADDI, the K comparisons (C) and STK_* (A).
  const auto immA = [&ip] { return int64_t{static_cast<int16_t>(INS->a)}; };
  const auto immC = [&ip] { return int64_t{static_cast<int16_t>(INS->c)}; };
  uint64_t ad = 0;

#define VM_FAULT(kind)                                      \
  do {                                                      \
    executed_ += executed;                                  \
    return raise(FaultKind::kind, pcOf(INS), depth, startSp); \
  } while (0)
#define VM_ADDR(width) \
  if (!checkedAddress(r[INS->b], INS->c, width, memSize, guard, ad)) VM_FAULT(InvalidPointer)
#define VM_LOAD_AT(T, expr)                  \
  {                                          \
    T v = loadLe<T>(mem + ad);               \
    r[INS->a] = (expr);                      \
  }                                          \
  VM_NEXT()
#define VM_STORE_AT(T, expr)     \
  storeLe<T>(mem + ad, (expr));  \
  VM_NEXT()
// Every register-relative load and store twice: checked, and quickened (no check: the entry
// check of the activation proved it inside memory).
#define VM_QUICK_ADDR() ad = r[INS->b] + INS->c
#define VM_LOAD(name, T, expr) \
  VM_CASE(name) VM_ADDR(sizeof(T)); VM_LOAD_AT(T, expr); \
  VM_QCASE(name) VM_QUICK_ADDR(); VM_LOAD_AT(T, expr)
#define VM_STORE(name, T, expr) \
  VM_CASE(name) VM_ADDR(sizeof(T)); VM_STORE_AT(T, expr); \
  VM_QCASE(name) VM_QUICK_ADDR(); VM_STORE_AT(T, expr)
#define VM_LOADA(T, expr)                \
  {                                      \
    T v = loadLe<T>(mem + INS->bx());    \
    r[INS->a] = (expr);                  \
  }                                      \
  VM_NEXT()
#define VM_STOREA(T, expr) storeLe<T>(mem + INS->bx(), (expr)); VM_NEXT()
#define VM_BIN(expr) { const uint64_t x = r[INS->b], y = r[INS->c]; r[INS->a] = (expr); } VM_NEXT()
#define VM_BINF(expr) { const double x = asF(r[INS->b]), y = asF(r[INS->c]); r[INS->a] = (expr); } VM_NEXT()
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
#define Q(name) &&quick_##name,
      VIRTCOM_VM_QUICK_OPS(Q) VIRTCOM_VM_SPECIAL_OPS(Q)
#undef Q
  };
  // The table's address in a register: hidden from the optimiser, which would otherwise
  // recompute it (one more x86 instruction) at every dispatch.
  void* const* labels = kLabels;
  asm("" : "+r"(labels));
#define VM_NEXT()                                  \
  do {                                             \
    if constexpr (kCounting) ++executed;           \
    goto* labels[static_cast<uint8_t>((ip++)->op)]; \
  } while (0)
#define VM_CASE(name) op_##name:
#define VM_QCASE(name) quick_##name:
  VM_NEXT();
#else
#define VM_NEXT() continue
#define VM_CASE(name) case static_cast<unsigned>(Op::name):
#define VM_QCASE(name) case static_cast<unsigned>(quickOpcode(QuickOp::name)):
  for (;;) {
    if constexpr (kCounting) ++executed;
    switch (static_cast<unsigned>((ip++)->op)) {
#endif

  VM_CASE(NOP) VM_NEXT();
  VM_CASE(MOV) r[INS->a] = r[INS->b]; VM_NEXT();
  VM_CASE(LDI) r[INS->a] = fromI(INS->sbx()); VM_NEXT();
  VM_CASE(LDK) r[INS->a] = constants[INS->bx()]; VM_NEXT();
  VM_CASE(SYSTIME) r[INS->a] = fromI(taskTimeNs_); ++timeReads_; VM_NEXT();

  VM_LOAD(LD_I8, int8_t, fromI(v));
  VM_LOAD(LD_U8, uint8_t, uint64_t{v});
  VM_LOAD(LD_I16, int16_t, fromI(v));
  VM_LOAD(LD_U16, uint16_t, uint64_t{v});
  VM_LOAD(LD_I32, int32_t, fromI(v));
  VM_LOAD(LD_U32, uint32_t, uint64_t{v});
  VM_LOAD(LD_64, uint64_t, v);
  VM_LOAD(LD_F32, float, fromF(static_cast<double>(v)));
  VM_CASE(LD_BIT)
    if (!checkedAddress(r[INS->b], 0, 1, memSize, guard, ad)) VM_FAULT(InvalidPointer);
  VM_QCASE(LD_BIT)
    r[INS->a] = (mem[r[INS->b]] >> (INS->c & 7u)) & 1u;
    VM_NEXT();

  VM_STORE(ST_8, uint8_t, static_cast<uint8_t>(r[INS->a]));
  VM_STORE(ST_16, uint16_t, static_cast<uint16_t>(r[INS->a]));
  VM_STORE(ST_32, uint32_t, static_cast<uint32_t>(r[INS->a]));
  VM_STORE(ST_64, uint64_t, r[INS->a]);
  VM_STORE(ST_F32, float, static_cast<float>(asF(r[INS->a])));
  VM_CASE(ST_BIT)
    if (!checkedAddress(r[INS->b], 0, 1, memSize, guard, ad)) VM_FAULT(InvalidPointer);
  VM_QCASE(ST_BIT) {
    uint8_t& byte = mem[r[INS->b]];
    const uint8_t mask = static_cast<uint8_t>(1u << (INS->c & 7u));
    byte = r[INS->a] != 0 ? (byte | mask) : (byte & ~mask);
  }
    VM_NEXT();

  VM_STORE(STK_8, uint8_t, static_cast<uint8_t>(immA()));
  VM_STORE(STK_16, uint16_t, static_cast<uint16_t>(immA()));
  VM_STORE(STK_32, uint32_t, static_cast<uint32_t>(immA()));
  VM_STORE(STK_64, uint64_t, fromI(immA()));

  VM_CASE(LDA_I8) VM_LOADA(int8_t, fromI(v));
  VM_CASE(LDA_U8) VM_LOADA(uint8_t, uint64_t{v});
  VM_CASE(LDA_I16) VM_LOADA(int16_t, fromI(v));
  VM_CASE(LDA_U16) VM_LOADA(uint16_t, uint64_t{v});
  VM_CASE(LDA_I32) VM_LOADA(int32_t, fromI(v));
  VM_CASE(LDA_U32) VM_LOADA(uint32_t, uint64_t{v});
  VM_CASE(LDA_64) VM_LOADA(uint64_t, v);
  VM_CASE(LDA_F32) VM_LOADA(float, fromF(static_cast<double>(v)));
  VM_CASE(STA_8) VM_STOREA(uint8_t, static_cast<uint8_t>(r[INS->a]));
  VM_CASE(STA_16) VM_STOREA(uint16_t, static_cast<uint16_t>(r[INS->a]));
  VM_CASE(STA_32) VM_STOREA(uint32_t, static_cast<uint32_t>(r[INS->a]));
  VM_CASE(STA_64) VM_STOREA(uint64_t, r[INS->a]);
  VM_CASE(STA_F32) VM_STOREA(float, static_cast<float>(asF(r[INS->a])));

  VM_CASE(COPY) {
    const uint64_t n = r[INS->c];
    uint64_t src = 0;
    if (!checkedAddress(r[INS->a], 0, n, memSize, guard, ad) ||
        !checkedAddress(r[INS->b], 0, n, memSize, guard, src))
      VM_FAULT(InvalidPointer);
    std::memmove(mem + ad, mem + src, n);
  }
    VM_NEXT();

#define VM_INDEX()                                                   \
  {                                                                  \
    const bc::IndexDesc& d = indexes[INS->c];                        \
    const int64_t k = asI(r[INS->b] - fromI(d.lo));                  \
    if (k < 0 || k >= int64_t{d.count}) VM_FAULT(IndexOutOfRange);   \
    r[INS->a] = fromI(k) * d.stride;                                 \
  }
  VM_CASE(INDEX) VM_INDEX();
  VM_NEXT();
  // INDEX, then the ADD after it (vm/quicken.hpp).
  VM_QCASE(INDEX_ADD) VM_INDEX();
  ++ip;
  if constexpr (kCounting) ++executed;
  VM_BIN(x + y);
#undef VM_INDEX

  VM_CASE(ADD) VM_BIN(x + y);
  VM_CASE(SUB) VM_BIN(x - y);
  VM_CASE(MUL) VM_BIN(x * y);
  VM_CASE(DIV_I)
    if (r[INS->c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(asI(y) == -1 ? 0 - x : fromI(asI(x) / asI(y)));
  VM_CASE(MOD_I)
    if (r[INS->c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(asI(y) == -1 ? 0 : fromI(asI(x) % asI(y)));
  VM_CASE(DIV_U)
    if (r[INS->c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(x / y);
  VM_CASE(MOD_U)
    if (r[INS->c] == 0) VM_FAULT(DivisionByZero);
    VM_BIN(x % y);
  VM_CASE(ADDI) r[INS->a] = r[INS->b] + fromI(immC()); VM_NEXT();
  VM_CASE(DIVK) r[INS->a] = fromI(asI(r[INS->b]) / int64_t{INS->c}); VM_NEXT();
  VM_CASE(MODK) r[INS->a] = fromI(asI(r[INS->b]) % int64_t{INS->c}); VM_NEXT();
  VM_CASE(NEG) r[INS->a] = 0 - r[INS->b]; VM_NEXT();
  VM_CASE(SEXT) {
    const unsigned bits = INS->c;
    const uint64_t v = r[INS->b];
    r[INS->a] = bits == 0 ? 0 : bits >= 64 ? v : fromI(asI(v << (64 - bits)) >> (64 - bits));
  }
    VM_NEXT();
  VM_CASE(ZEXT) {
    const unsigned bits = INS->c;
    const uint64_t v = r[INS->b];
    r[INS->a] = bits >= 64 ? v : v & ((uint64_t{1} << bits) - 1);
  }
    VM_NEXT();
  VM_CASE(BAND) VM_BIN(x & y);
  VM_CASE(BOR) VM_BIN(x | y);
  VM_CASE(BXOR) VM_BIN(x ^ y);
  VM_CASE(BNOT) r[INS->a] = ~r[INS->b]; VM_NEXT();
  VM_CASE(LNOT) r[INS->a] = r[INS->b] == 0; VM_NEXT();
  VM_CASE(SHL) VM_BIN(y < 64 ? x << y : 0);
  VM_CASE(SHR) VM_BIN(y < 64 ? x >> y : 0);

  VM_CASE(EQ) VM_BIN(x == y);
  VM_CASE(NE) VM_BIN(x != y);
  VM_CASE(LT_I) VM_BIN(asI(x) < asI(y));
  VM_CASE(LE_I) VM_BIN(asI(x) <= asI(y));
  VM_CASE(LT_U) VM_BIN(x < y);
  VM_CASE(LE_U) VM_BIN(x <= y);
  VM_CASE(EQK) r[INS->a] = asI(r[INS->b]) == immC(); VM_NEXT();
  VM_CASE(NEK) r[INS->a] = asI(r[INS->b]) != immC(); VM_NEXT();
  VM_CASE(LTK) r[INS->a] = asI(r[INS->b]) < immC(); VM_NEXT();
  VM_CASE(LEK) r[INS->a] = asI(r[INS->b]) <= immC(); VM_NEXT();
  VM_CASE(GTK) r[INS->a] = asI(r[INS->b]) > immC(); VM_NEXT();
  VM_CASE(GEK) r[INS->a] = asI(r[INS->b]) >= immC(); VM_NEXT();
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
  VM_CASE(NEG_F) r[INS->a] = fromF(-asF(r[INS->b])); VM_NEXT();
  VM_CASE(RND_F32) r[INS->a] = fromF(static_cast<float>(asF(r[INS->b]))); VM_NEXT();

  VM_CASE(I2F) r[INS->a] = fromF(static_cast<double>(asI(r[INS->b]))); VM_NEXT();
  VM_CASE(U2F) r[INS->a] = fromF(static_cast<double>(r[INS->b])); VM_NEXT();
  VM_CASE(F2I) r[INS->a] = fromI(roundToI64(asF(r[INS->b]))); VM_NEXT();
  VM_CASE(F2I_TRUNC) r[INS->a] = fromI(truncToI64(asF(r[INS->b]))); VM_NEXT();
  VM_CASE(F2U) r[INS->a] = roundToU64(asF(r[INS->b])); VM_NEXT();

  VM_CASE(JMP)
    VM_BACKWARD_CHECK(INS->sbx());
    ip += INS->sbx();
    VM_NEXT();
  VM_CASE(JZ)
    if (r[INS->a] == 0) {
      VM_BACKWARD_CHECK(INS->sbx());
      ip += INS->sbx();
    }
    VM_NEXT();
  VM_CASE(JNZ)
    if (r[INS->a] != 0) {
      VM_BACKWARD_CHECK(INS->sbx());
      ip += INS->sbx();
    }
    VM_NEXT();
  // Fused compare-and-branch: register forms jump by C, constant forms by B (the constant is C).
#define VM_BRANCH_IF(cond, offset)          \
  if (cond) {                               \
    const int32_t off = (offset);           \
    VM_BACKWARD_CHECK(off);                 \
    ip += off;                              \
  }                                         \
  VM_NEXT()
  VM_CASE(JEQ) VM_BRANCH_IF(r[INS->a] == r[INS->b], static_cast<int16_t>(INS->c));
  VM_CASE(JNE) VM_BRANCH_IF(r[INS->a] != r[INS->b], static_cast<int16_t>(INS->c));
  VM_CASE(JLT_I) VM_BRANCH_IF(asI(r[INS->a]) < asI(r[INS->b]), static_cast<int16_t>(INS->c));
  VM_CASE(JLE_I) VM_BRANCH_IF(asI(r[INS->a]) <= asI(r[INS->b]), static_cast<int16_t>(INS->c));
  VM_CASE(JLT_U) VM_BRANCH_IF(r[INS->a] < r[INS->b], static_cast<int16_t>(INS->c));
  VM_CASE(JLE_U) VM_BRANCH_IF(r[INS->a] <= r[INS->b], static_cast<int16_t>(INS->c));
  VM_CASE(JEQK) VM_BRANCH_IF(asI(r[INS->a]) == immC(), static_cast<int16_t>(INS->b));
  VM_CASE(JNEK) VM_BRANCH_IF(asI(r[INS->a]) != immC(), static_cast<int16_t>(INS->b));
  VM_CASE(JLTK) VM_BRANCH_IF(asI(r[INS->a]) < immC(), static_cast<int16_t>(INS->b));
  VM_CASE(JLEK) VM_BRANCH_IF(asI(r[INS->a]) <= immC(), static_cast<int16_t>(INS->b));
  VM_CASE(JGTK) VM_BRANCH_IF(asI(r[INS->a]) > immC(), static_cast<int16_t>(INS->b));
  VM_CASE(JGEK) VM_BRANCH_IF(asI(r[INS->a]) >= immC(), static_cast<int16_t>(INS->b));
  // The interpreter's specialisations (vm/quicken.hpp, VIRTCOM_VM_SPECIAL_OPS).
  VM_QCASE(SEXT8) r[INS->a] = fromI(static_cast<int8_t>(r[INS->b])); VM_NEXT();
  VM_QCASE(SEXT16) r[INS->a] = fromI(static_cast<int16_t>(r[INS->b])); VM_NEXT();
  VM_QCASE(SEXT32) r[INS->a] = fromI(static_cast<int32_t>(r[INS->b])); VM_NEXT();
  VM_QCASE(ZEXT8) r[INS->a] = static_cast<uint8_t>(r[INS->b]); VM_NEXT();
  VM_QCASE(ZEXT16) r[INS->a] = static_cast<uint16_t>(r[INS->b]); VM_NEXT();
  VM_QCASE(ZEXT32) r[INS->a] = static_cast<uint32_t>(r[INS->b]); VM_NEXT();
  // ADDI a, a, k; ST_w a, base, off; LD_Iw a, base, off (what the store left: the sum's low w
  // bits, sign-extended); then the JLE_I that follows, as itself.
#define VM_FOR_NEXT(T)                                                  \
  {                                                                     \
    const T v = static_cast<T>(r[INS->b] + static_cast<uint64_t>(immC())); \
    storeLe<T>(mem + r[ip->b] + ip->c, v);                              \
    r[INS->a] = fromI(static_cast<std::make_signed_t<T>>(v));           \
    ip += 3;                                                            \
    if constexpr (kCounting) executed += 3;                             \
  }                                                                     \
  VM_BRANCH_IF(asI(r[INS->a]) <= asI(r[INS->b]), static_cast<int16_t>(INS->c))
  VM_QCASE(FOR_NEXT_I16) VM_FOR_NEXT(uint16_t);
  VM_QCASE(FOR_NEXT_I32) VM_FOR_NEXT(uint32_t);
#undef VM_FOR_NEXT
  VM_CASE(ENTER) {
    const bc::PouInfo& p = pous[INS->bx()];
    if (sp + p.frameSize > memSize) VM_FAULT(StackOverflow);
    std::memcpy(mem + sp, image + p.frameTemplate, p.frameSize);
    r[INS->a] = sp;
    sp += p.frameSize;
  }
    VM_NEXT();
  // A frame of 0 bytes: sp <= memSize always holds, so nothing to check or copy.
  VM_QCASE(ENTER0) r[INS->a] = sp; VM_NEXT();
// The callee's fp and this are read once, after the check that its window fits.
#define VM_CALL()                                                                  \
  {                                                                                \
    const PouEntry& p = entry[INS->bx()];                                          \
    const uint16_t window = INS->a;                                                \
    if (remaining == 0) VM_FAULT(WatchdogBudget);                                  \
    --remaining;                                                                   \
    const uint64_t newBase = uint64_t{base} + window;                              \
    if (depth >= maxDepth || newBase + p.numRegs > regCount) VM_FAULT(StackOverflow); \
    const uint64_t fp = r[window], self = r[window + 1];                           \
    frames_[depth++] = CallFrame{ip, base, fp, code};                              \
    code = p.admits(fp, self) ? quick : plain;                                     \
    base = static_cast<uint32_t>(newBase);                                         \
    r = regs + base;                                                               \
    ip = code + p.codeStart;                                                       \
  }                                                                                \
  VM_NEXT()
  VM_CASE(CALL) VM_CALL();
  // ENTER0, then the MOV and the CALL after it (vm/quicken.hpp).
  VM_QCASE(ENTER0_CALL)
    r[INS->a] = sp;
    r[ip->a] = r[ip->b];
    ip += 2;
    if constexpr (kCounting) executed += 2;
    VM_CALL();
#undef VM_CALL
  VM_CASE(CALLN) {
    const FaultKind k = kNatives[INS->bx()](r + INS->a, nctx);
    if (k != FaultKind::None) {
      executed_ += executed;
      return raise(k, pcOf(INS), depth, startSp);
    }
  }
    VM_NEXT();
  VM_CASE(CALLFB)
    if (!checkedAddress(r[INS->a], 0, kNativeFbSizes[INS->bx()], memSize, guard, ad)) VM_FAULT(InvalidPointer);
    if (kNativeFbs[INS->bx()](mem + ad, taskTimeNs_)) ++timeReads_;
    VM_NEXT();
  VM_QCASE(CALLFB)
    if (kNativeFbs[INS->bx()](mem + r[INS->a], taskTimeNs_)) ++timeReads_;
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
      code = f.code;
      ip = f.returnIp;
    }
    VM_NEXT();
  VM_CASE(COVER) storeLe<uint64_t>(mem + INS->bx(), loadLe<uint64_t>(mem + INS->bx()) + 1); VM_NEXT();
  VM_CASE(TRAP) {
    const uint32_t kind = INS->bx();
    executed_ += executed;
    return raise(kind <= static_cast<uint32_t>(FaultKind::SubrangeViolation) && kind != 0
                     ? static_cast<FaultKind>(kind)
                     : FaultKind::InvalidEnumValue,
                 pcOf(INS), depth, startSp);
  }

#if !VIRTCOM_VM_COMPUTED_GOTO
      default: break;  // none after verification
    }
    executed_ += executed;
    return raise(FaultKind::InvalidPointer, pcOf(INS), depth, startSp);  // unreachable after verification
  }
#endif
#undef INS
#undef VM_FAULT
#undef VM_ADDR
#undef VM_LOAD_AT
#undef VM_STORE_AT
#undef VM_QUICK_ADDR
#undef VM_LOAD
#undef VM_STORE
#undef VM_LOADA
#undef VM_STOREA
#undef VM_BIN
#undef VM_BINF
#undef VM_BACKWARD_CHECK
#undef VM_BRANCH_IF
#undef VM_NEXT
#undef VM_CASE
#undef VM_QCASE
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
