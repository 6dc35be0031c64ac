#include "aot/c_source.hpp"

#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

#include "aot/opcode_snippets.hpp"
#include "aot/register_plan.hpp"
#include "vm/compiled.hpp"
#include "vm/natives.hpp"

namespace virtcom::aot {

namespace {

using bc::FaultKind;
using bc::Instr;
using bc::Op;

#define VIRTCOM_STRINGIFY(...) #__VA_ARGS__
#define VIRTCOM_EXPAND_STRINGIFY(...) VIRTCOM_STRINGIFY(__VA_ARGS__)
constexpr std::string_view kAbiText = VIRTCOM_EXPAND_STRINGIFY(VIRTCOM_AOT_ABI);

// The native FBs' C code (vm/native_fbs_c.def) and the member accessors it uses, the C twins
// of those in vm/natives_fb.cpp (little endian only, which the prelude checks).
#define NATIVE_FBS_C(...) constexpr std::string_view kNativeFbCode = #__VA_ARGS__;
#include "vm/native_fbs_c.def"
#undef NATIVE_FBS_C
#define FB(name)
#define M(fb, member, offset, ctype)                                                                   \
  VIRTCOM_STRINGIFY(static inline ctype get_##fb##_##member(const uint8_t* i) {                        \
    ctype v; __builtin_memcpy(&v, i + (offset), sizeof v); return v; }                                 \
  static inline void set_##fb##_##member(uint8_t* i, ctype v) { __builtin_memcpy(i + (offset), &v, sizeof v); }) "\n"
constexpr std::string_view kNativeFbAccessors =
#include "bytecode/native_fbs.def"
    ;
#undef M
#undef FB
constexpr std::string_view kNativeFbNames[] = {
#define FB(name) #name,
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB
};

// Shared by every generated function. The helpers mirror vm/value.hpp (checkedAddress,
// roundToI64, ...) for a little-endian host; a big-endian one refuses to compile, and the
// caller then falls back to the interpreter.
constexpr std::string_view kPrelude = R"(
#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "virtcom AOT code assumes a little-endian host"
#endif
typedef uint8_t (*vc_native)(uint64_t*, const void*);
#define LDM(T, a) ({ T v_; __builtin_memcpy(&v_, mem + (a), sizeof v_); v_; })
#define STM(T, a, x) do { T v_ = (T)(x); __builtin_memcpy(mem + (a), &v_, sizeof v_); } while (0)
#define FAIL(k) do { result = (k); goto fail; } while (0)
#define FAULT(pc, k) do { c->faultPc = (pc); FAIL(k); } while (0)
#define BUDGET(pc) do { if (remaining == 0) FAULT(pc, FK_WATCHDOG); --remaining; } while (0)
static inline double F(uint64_t v) { double d; __builtin_memcpy(&d, &v, 8); return d; }
static inline uint64_t U(double d) { uint64_t v; __builtin_memcpy(&v, &d, 8); return v; }
static inline int chk(uint64_t base, uint64_t off, uint64_t width, uint64_t* ad) {
  const uint64_t a = base + off;
  *ad = a;
  if (a < base || a < GUARD || MSZ < width) return 0;
  return a <= MSZ - width;
}
static inline uint64_t sext(uint64_t v, unsigned bits) {
  return bits == 0 ? 0 : bits >= 64 ? v : (uint64_t)((int64_t)(v << (64 - bits)) >> (64 - bits));
}
static inline uint64_t zext(uint64_t v, unsigned bits) { return bits >= 64 ? v : v & ((1ull << bits) - 1); }
static inline int64_t sati(double r) {
  if (r != r) return 0;
  if (r >= 9223372036854775808.0) return INT64_MAX;
  if (r < -9223372036854775808.0) return INT64_MIN;
  return (int64_t)r;
}
static inline int64_t rtoi(double f) { return sati(__builtin_round(f)); }
static inline int64_t ttoi(double f) { return sati(__builtin_trunc(f)); }
static inline uint64_t rtou(double f) {
  if (f != f) return 0;
  const double r = __builtin_round(f);
  if (r <= 0.0) return 0;
  if (r >= 18446744073709551616.0) return UINT64_MAX;
  return (uint64_t)r;
}
)";

// Appends rather than `"r" + std::to_string(i)`, which trips GCC 12's -Wrestrict (PR 105329).
std::string numbered(const char* prefix, uint64_t n) {
  std::string s = prefix;
  s += std::to_string(n);
  return s;
}
std::string reg(unsigned i) { return numbered("r", i); }
std::string label(uint32_t pc) { return numbered("L", pc); }
std::string pouFunction(uint32_t pou) { return numbered("pou_", pou); }
std::string i64Literal(int64_t v) {
  // INT64_MIN has no literal form.
  return v == INT64_MIN ? "INT64_MIN" : "((int64_t)" + std::to_string(v) + "LL)";
}
std::string u64Literal(uint64_t v) { return std::to_string(v) + "ull"; }

uint32_t jumpTarget(uint32_t pc, const Instr& ins) { return static_cast<uint32_t>(bc::branchTarget(pc, ins)); }
bool isJump(Op op) { return bc::isBranch(op); }

// The fault kind TRAP raises for its Bx, as Machine::execute maps it.
int trapKind(uint32_t bx) {
  return bx != 0 && bx <= static_cast<uint32_t>(FaultKind::SubrangeViolation) ? static_cast<int>(bx)
                                                                               : static_cast<int>(FaultKind::InvalidEnumValue);
}

// Leaves up to this many instructions are inlined into their callers by the C compiler
// (always_inline): a user FB call then costs no C call, and the register stores around it
// become plain copies the compiler can forward.
constexpr uint32_t kInlineLeafInstructions = 64;

bool isSmallLeaf(const bc::Module& m, const bc::PouInfo& p) {
  if (p.codeSize > kInlineLeafInstructions) return false;
  const auto begin = m.code.begin() + p.codeStart;
  return std::none_of(begin, begin + p.codeSize, [](const Instr& ins) { return ins.op == Op::CALL; });
}

// `restrict`: the context is reached only through `c` while a POU runs, so the C compiler may
// keep its fields in registers across stores to the memory image.
std::string pouSignature(const bc::Module& m, uint32_t pou) {
  const char* linkage = isSmallLeaf(m, m.pous[pou]) ? "static inline __attribute__((always_inline)) int " : "static int ";
  return linkage + pouFunction(pou) + "(struct AotContext* restrict c, uint32_t base, uint32_t depth)";
}

class PouWriter {
 public:
  PouWriter(const bc::Module& m, uint32_t pou, const RegisterPlan& plan, std::string& out)
      : m_(m), pou_(m.pous[pou]), index_(pou), plan_(plan), regs_(plan.pous[pou]), out_(out) {}

  void write() {
    const uint32_t begin = pou_.codeStart, end = pou_.codeStart + pou_.codeSize;
    std::vector<bool> targets(pou_.codeSize, false);
    for (uint32_t pc = begin; pc < end; ++pc)
      if (isJump(m_.code[pc].op)) targets[jumpTarget(pc, m_.code[pc]) - begin] = true;

    out_ += pouSignature(m_, index_) + " {\n";
    out_ += "  uint8_t* const mem = c->mem;\n  uint64_t* const w = c->regs + base;\n";
    out_ += "  uint64_t remaining = c->remaining, ad;\n  int result;\n  (void)depth; (void)ad;\n";
    for (unsigned r = 0; r < pou_.numRegs; ++r)
      out_ += "  uint64_t " + reg(r) + (regs_.loadOnEntry[r] ? " = w[" + std::to_string(r) + "];\n" : " = 0;\n");
    for (uint32_t pc = begin; pc < end; ++pc) {
      if (targets[pc - begin]) out_ += label(pc) + ":;\n";
      out_ += "  ";
      expand(pc, m_.code[pc]);
      out_ += "\n";
    }
    // A fault leaves without the write-back: no bytecode reads those registers afterwards.
    out_ += "finish:\n  ";
    for (unsigned r = 0; r < pou_.numRegs; ++r)
      if (regs_.writeBack[r]) out_ += "w[" + std::to_string(r) + "] = " + reg(r) + "; ";
    out_ += "\n  c->remaining = remaining;\n  return 0;\nfail:\n  return result;\n}\n\n";
  }

 private:
  // The caller's registers around a CALL at pc: before it, those the callee may read and those
  // read after it; after it, the latter are reloaded (the callee may have changed them).
  void callRegs(uint32_t pc, const Instr& ins, bool load) {
    const RegisterSet& liveAfter = regs_.liveAfterCall[pc - pou_.codeStart];
    const RegisterSet& inputs = plan_.inputs[ins.bx()];
    for (uint32_t r = ins.a; r < pou_.numRegs; ++r) {
      const bool calleeReads = r - ins.a < inputs.size() && inputs[r - ins.a];
      if (!liveAfter[r] && (load || !calleeReads)) continue;
      const std::string slot = "w[" + std::to_string(r) + "]";
      out_ += load ? reg(r) + " = " + slot + "; " : slot + " = " + reg(r) + "; ";
    }
  }
  // A native's arguments go through a_[] and come back from it.
  void nativeArgs(const Instr& ins, bool load) {
    for (unsigned i = 0; i < nativeArity(ins); ++i) {
      const std::string slot = "a_[" + std::to_string(i) + "]";
      out_ += load ? reg(ins.a + i) + " = " + slot + "; " : slot + " = " + reg(ins.a + i) + "; ";
    }
  }
  static unsigned nativeArity(const Instr& ins) {
    return std::max(1u, bc::nativeArity(static_cast<bc::Native>(ins.bx())));
  }
  void passRegs(uint32_t pc, const Instr& ins, bool load) {
    if (ins.op == Op::CALLN) nativeArgs(ins, load);
    else callRegs(pc, ins, load);
  }

  void expand(uint32_t pc, const Instr& ins) {
    const std::string_view text = opcodeSnippet(ins.op);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] != '%' || i + 1 == text.size()) {
        out_ += text[i];
        continue;
      }
      placeholder(text[++i], pc, ins);
    }
  }

  void placeholder(char p, uint32_t pc, const Instr& ins) {
    switch (p) {
      case 'A': out_ += reg(ins.a); break;
      case 'B': out_ += reg(ins.b); break;
      case 'C': out_ += reg(ins.c); break;
      case 'a': out_ += std::to_string(ins.a); break;
      case 'c': out_ += std::to_string(ins.c); break;
      case 'i': out_ += i64Literal(static_cast<int16_t>(ins.a)); break;
      case 'k': out_ += i64Literal(static_cast<int16_t>(ins.c)); break;
      case 'x': out_ += u64Literal(ins.bx()); break;
      case 'S': out_ += i64Literal(ins.sbx()); break;
      case 'p': out_ += std::to_string(pc) + "u"; break;
      case 'T': out_ += label(jumpTarget(pc, ins)); break;
      case 'J': if (bc::branchOffset(ins) < 0) out_ += "BUDGET(" + std::to_string(pc) + "u);"; break;
      case 'K': out_ += u64Literal(m_.constants[ins.bx()]); break;
      case 'L': out_ += i64Literal(m_.indexes[ins.c].lo); break;
      case 'N': out_ += i64Literal(m_.indexes[ins.c].count); break;
      case 'Z': out_ += u64Literal(m_.indexes[ins.c].stride); break;
      case 'F': out_ += u64Literal(m_.pous[ins.bx()].frameSize); break;
      case 'G': out_ += u64Literal(m_.pous[ins.bx()].frameTemplate); break;
      case 'R': out_ += u64Literal(m_.pous[ins.bx()].numRegs); break;
      case 'P': out_ += pouFunction(ins.bx()); break;
      case 'W': out_ += u64Literal(vm::kNativeFbSizes[ins.bx()]); break;
      case 'f': out_ += "fbStep_" + std::string(kNativeFbNames[ins.bx()]); break;
      case 'n': out_ += std::to_string(nativeArity(ins)); break;
      case 's': passRegs(pc, ins, false); break;
      case 'r': passRegs(pc, ins, true); break;
      case 'q': out_ += std::to_string(trapKind(ins.bx())); break;
      default: out_ += '%'; out_ += p; break;
    }
  }

  const bc::Module& m_;
  const bc::PouInfo& pou_;
  const uint32_t index_;
  const RegisterPlan& plan_;
  const PouRegisters& regs_;
  std::string& out_;
};

void writeFaultKinds(std::string& out) {
  const std::array<std::pair<const char*, FaultKind>, 5> kinds{{{"FK_DIV", FaultKind::DivisionByZero},
                                                                {"FK_INDEX", FaultKind::IndexOutOfRange},
                                                                {"FK_PTR", FaultKind::InvalidPointer},
                                                                {"FK_STACK", FaultKind::StackOverflow},
                                                                {"FK_WATCHDOG", FaultKind::WatchdogBudget}}};
  for (const auto& [name, kind] : kinds)
    out += std::string("#define ") + name + " " + std::to_string(static_cast<int>(kind)) + "\n";
}

}  // namespace

std::string generateCSource(const bc::Module& m) {
  std::string out = "/* generated by virtcom from bytecode; do not edit */\n#include <stdbool.h>\n#include <stdint.h>\n";
  out += kAbiText;
  out += "\n#define MSZ " + u64Literal(m.memorySize()) + "\n#define GUARD " + u64Literal(bc::Module::kNullGuard) +
         "\n#define STATIC " + u64Literal(m.staticSize) + "\n";
  writeFaultKinds(out);
  out += kPrelude;
  out += kNativeFbAccessors;
  out += kNativeFbCode;
  out += "\n";
  const auto count = static_cast<uint32_t>(m.pous.size());
  for (uint32_t p = 0; p < count; ++p) out += pouSignature(m, p) + ";\n";
  out += "\n";
  const RegisterPlan plan = planRegisters(m);
  for (uint32_t p = 0; p < count; ++p) PouWriter(m, p, plan, out).write();
  out += std::string("const AotEntry ") + kEntriesSymbol + "[] = {";
  for (uint32_t p = 0; p < count; ++p) out += (p ? ", " : "") + pouFunction(p);
  out += "};\n";
  out += std::string("const uint32_t ") + kCountSymbol + " = " + std::to_string(count) + "u;\n";
  out += std::string("const uint32_t ") + kAbiSymbol + " = " + std::to_string(vm::kAotAbiVersion) + "u;\n";
  return out;
}

}  // namespace virtcom::aot
