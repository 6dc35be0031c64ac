#include "aot/c_source.hpp"

#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

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

#define C(name, text) constexpr std::string_view kC_##name = text;
#include "aot/opcodes_c.def"
#undef C

// Indexed by Op; an opcode missing from opcodes_c.def fails to compile here.
constexpr std::string_view kSnippets[] = {
#define X(name, fmt, meaning) kC_##name,
#include "bytecode/opcodes.def"
#undef X
};
static_assert(std::size(kSnippets) == static_cast<size_t>(Op::Count_));

// Shared by every generated function. The helpers mirror vm/value.hpp (checkedAddress,
// roundToI64, ...) for a little-endian host; a big-endian one refuses to compile, and the
// caller then falls back to the interpreter.
constexpr std::string_view kPrelude = R"(
#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "virtcom AOT code assumes a little-endian host"
#endif
typedef uint8_t (*vc_native)(uint64_t*, const void*);
typedef bool (*vc_native_fb)(uint8_t*, int64_t);
#define LDM(T, a) ({ T v_; __builtin_memcpy(&v_, mem + (a), sizeof v_); v_; })
#define STM(T, a, x) do { T v_ = (T)(x); __builtin_memcpy(mem + (a), &v_, sizeof v_); } while (0)
#define RETURN(k) do { result = (k); goto finish; } while (0)
#define FAULT(pc, k) do { c->faultPc = (pc); RETURN(k); } while (0)
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
static inline int64_t rtoi(double f) {
  if (f != f) return 0;
  const double r = __builtin_round(f);
  if (r >= 9223372036854775808.0) return INT64_MAX;
  if (r < -9223372036854775808.0) return INT64_MIN;
  return (int64_t)r;
}
static inline int64_t ttoi(double f) {
  if (f != f) return 0;
  const double r = __builtin_trunc(f);
  if (r >= 9223372036854775808.0) return INT64_MAX;
  if (r < -9223372036854775808.0) return INT64_MIN;
  return (int64_t)r;
}
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

uint32_t jumpTarget(uint32_t pc, const Instr& ins) { return static_cast<uint32_t>(int64_t{pc} + 1 + ins.sbx()); }
bool isJump(Op op) { return op == Op::JMP || op == Op::JZ || op == Op::JNZ; }

// The fault kind TRAP raises for its Bx, as Machine::execute maps it.
int trapKind(uint32_t bx) {
  return bx != 0 && bx <= static_cast<uint32_t>(FaultKind::SubrangeViolation) ? static_cast<int>(bx)
                                                                               : static_cast<int>(FaultKind::InvalidEnumValue);
}

// For every POU, how many registers from its window base its callers can read back after
// it returns: a caller at window A reloads its registers A.. up to the end of its own window,
// or further if its own callers read beyond that (register windows overlap). A fixed point
// over the call graph; recursion cannot raise it further. The epilogue writes back only these,
// so a program's top-level POUs write back none: keeping every register's last value alive
// until the end of the function costs the generated code up to 40% (bits, fb_calls).
std::vector<uint32_t> callerVisibleRegisters(const bc::Module& m) {
  std::vector<uint32_t> visible(m.pous.size(), 0);
  for (bool changed = true; changed;) {
    changed = false;
    for (uint32_t p = 0; p < m.pous.size(); ++p) {
      const bc::PouInfo& caller = m.pous[p];
      const uint32_t extent = std::max<uint32_t>(caller.numRegs, visible[p]);
      for (uint32_t pc = caller.codeStart; pc < caller.codeStart + caller.codeSize; ++pc) {
        const Instr& ins = m.code[pc];
        if (ins.op != Op::CALL || ins.a >= extent) continue;
        uint32_t& v = visible[ins.bx()];
        if (extent - ins.a > v) {
          v = extent - ins.a;
          changed = true;
        }
      }
    }
  }
  return visible;
}

class PouWriter {
 public:
  PouWriter(const bc::Module& m, uint32_t pou, uint32_t visibleRegs, std::string& out)
      : m_(m), pou_(m.pous[pou]), visibleRegs_(std::min<uint32_t>(visibleRegs, m.pous[pou].numRegs)), out_(out) {}

  void write(uint32_t index) {
    const uint32_t begin = pou_.codeStart, end = pou_.codeStart + pou_.codeSize;
    std::vector<bool> targets(pou_.codeSize, false);
    for (uint32_t pc = begin; pc < end; ++pc)
      if (isJump(m_.code[pc].op)) targets[jumpTarget(pc, m_.code[pc]) - begin] = true;

    out_ += "static int " + pouFunction(index) + "(struct AotContext* c, uint32_t base, uint32_t depth) {\n";
    out_ += "  uint8_t* const mem = c->mem;\n  uint64_t* const w = c->regs + base;\n";
    out_ += "  uint64_t remaining = c->remaining, ad;\n  int result;\n  (void)depth; (void)ad;\n";
    for (unsigned r = 0; r < pou_.numRegs; ++r) out_ += "  uint64_t " + reg(r) + " = w[" + std::to_string(r) + "];\n";
    for (uint32_t pc = begin; pc < end; ++pc) {
      if (targets[pc - begin]) out_ += label(pc) + ":;\n";
      out_ += "  ";
      expand(pc, m_.code[pc]);
      out_ += "\n";
    }
    out_ += "finish:\n  ";
    copyRegs("w", 0, visibleRegs_, false, 0);
    out_ += "\n  c->remaining = remaining;\n  return result;\n}\n\n";
  }

 private:
  void copyRegs(std::string_view to, unsigned from, unsigned count, bool load, uint32_t windowStart) {
    for (unsigned i = 0; i < count; ++i) {
      const std::string slot = std::string(to) + "[" + std::to_string(from - windowStart + i) + "]";
      out_ += load ? reg(from + i) + " = " + slot + "; " : slot + " = " + reg(from + i) + "; ";
    }
  }
  // The registers whose values a call can see or change: for CALL the caller's registers from
  // A up (the callee's window and everything beyond it), for CALLN its arguments.
  void callRegs(const Instr& ins, bool load) {
    if (ins.op == Op::CALLN) {
      copyRegs("a_", ins.a, nativeArgs(ins), load, ins.a);
    } else {
      copyRegs("w", ins.a, pou_.numRegs - ins.a, load, 0);
    }
  }
  static unsigned nativeArgs(const Instr& ins) {
    return std::max(1u, bc::nativeArity(static_cast<bc::Native>(ins.bx())));
  }

  void expand(uint32_t pc, const Instr& ins) {
    const std::string_view text = kSnippets[static_cast<size_t>(ins.op)];
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
      case 'J': if (ins.sbx() < 0) out_ += "BUDGET(" + std::to_string(pc) + "u);"; break;
      case 'K': out_ += u64Literal(m_.constants[ins.bx()]); break;
      case 'L': out_ += i64Literal(m_.indexes[ins.c].lo); break;
      case 'N': out_ += i64Literal(m_.indexes[ins.c].count); break;
      case 'Z': out_ += u64Literal(m_.indexes[ins.c].stride); break;
      case 'F': out_ += u64Literal(m_.pous[ins.bx()].frameSize); break;
      case 'G': out_ += u64Literal(m_.pous[ins.bx()].frameTemplate); break;
      case 'R': out_ += u64Literal(m_.pous[ins.bx()].numRegs); break;
      case 'P': out_ += pouFunction(ins.bx()); break;
      case 'W': out_ += u64Literal(vm::kNativeFbSizes[ins.bx()]); break;
      case 'n': out_ += std::to_string(nativeArgs(ins)); break;
      case 's': callRegs(ins, false); break;
      case 'r': callRegs(ins, true); break;
      case 'q': out_ += std::to_string(trapKind(ins.bx())); break;
      default: out_ += '%'; out_ += p; break;
    }
  }

  const bc::Module& m_;
  const bc::PouInfo& pou_;
  const uint32_t visibleRegs_;
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
  const auto count = static_cast<uint32_t>(m.pous.size());
  for (uint32_t p = 0; p < count; ++p)
    out += "static int " + pouFunction(p) + "(struct AotContext* c, uint32_t base, uint32_t depth);\n";
  out += "\n";
  const std::vector<uint32_t> visible = callerVisibleRegisters(m);
  for (uint32_t p = 0; p < count; ++p) PouWriter(m, p, visible[p], out).write(p);
  out += std::string("const AotEntry ") + kEntriesSymbol + "[] = {";
  for (uint32_t p = 0; p < count; ++p) out += (p ? ", " : "") + pouFunction(p);
  out += "};\n";
  out += std::string("const uint32_t ") + kCountSymbol + " = " + std::to_string(count) + "u;\n";
  out += std::string("const uint32_t ") + kAbiSymbol + " = " + std::to_string(vm::kAotAbiVersion) + "u;\n";
  return out;
}

}  // namespace virtcom::aot
