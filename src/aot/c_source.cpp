#include "aot/c_source.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "aot/opcode_snippets.hpp"
#include "aot/register_plan.hpp"
#include "core/content_hash.hpp"
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
// The pure natives' C code (vm/natives_pure_c.def), and which natives it covers: a CALLN of
// one of those calls pureNative_NAME, which the C compiler inlines, instead of the interpreter's
// function pointer.
#define NATIVES_PURE_C(...) constexpr std::string_view kPureNativeCode = #__VA_ARGS__;
#define PURE_NATIVE(name)
#include "vm/natives_pure_c.def"
#undef PURE_NATIVE
#undef NATIVES_PURE_C
constexpr std::pair<bc::Native, std::string_view> kPureNatives[] = {
#define NATIVES_PURE_C(...)
#define PURE_NATIVE(name) {bc::Native::name, #name},
#include "vm/natives_pure_c.def"
#undef PURE_NATIVE
#undef NATIVES_PURE_C
};
// The name of native `n` if vm/natives_pure_c.def has it, else empty.
std::string_view pureNativeName(uint32_t n) {
  for (const auto& [native, name] : kPureNatives)
    if (static_cast<uint32_t>(native) == n) return name;
  return {};
}
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
/* Register-relative: the address is (mem + base) + offset, so the C compiler sees accesses at
   different constant offsets from one base as disjoint and keeps values in registers across
   stores to other members of the same instance or frame. */
#define LDR(T, b, o) ({ T v_; __builtin_memcpy(&v_, mem + (b) + (o), sizeof v_); v_; })
#define STR(T, b, o, x) do { T v_ = (T)(x); __builtin_memcpy(mem + (b) + (o), &v_, sizeof v_); } while (0)
#define FAIL(k) do { result = (k); goto fail; } while (0)
#define FAULT(pc, k) do { c->faultPc = (pc); FAIL(k); } while (0)
#define BUDGET(pc) do { if (remaining == 0) FAULT(pc, FK_WATCHDOG); --remaining; } while (0)
static inline double F(uint64_t v) { double d; __builtin_memcpy(&d, &v, 8); return d; }
static inline uint64_t U(double d) { uint64_t v; __builtin_memcpy(&v, &d, 8); return v; }
/* checkedAddress as one range test on the base: base + off lies in [GUARD, MSZ - width] without
   overflow exactly when base lies in [lo, hi] below. off and width are constants but in COPY,
   so lo and hi fold and the test is one subtraction and one unsigned compare. */
static inline int chk(uint64_t base, uint64_t off, uint64_t width) {
  if (MSZ < width || MSZ - width < off) return 0;
  const uint64_t lo = off < GUARD ? GUARD - off : 0, hi = MSZ - width - off;
  return lo <= hi && base - lo <= hi - lo;
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
std::string label(uint32_t offset) { return numbered("L", offset); }
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

// POUs bigger than this are cut into functions of about this many instructions (chunkStarts).
constexpr uint32_t kChunkInstructions = 1000;

// Leaves up to this many instructions are inlined into their callers by the C compiler
// (always_inline): a user FB call then costs no C call, and the register stores around it
// become plain copies the compiler can forward. Every unit that calls one carries a copy.
constexpr uint32_t kInlineLeafInstructions = 64;

bool isSmallLeaf(const bc::Module& m, const bc::PouInfo& p) {
  if (p.codeSize > kInlineLeafInstructions) return false;
  const auto begin = m.code.begin() + p.codeStart;
  return std::none_of(begin, begin + p.codeSize, [](const Instr& ins) { return ins.op == Op::CALL; });
}

// Per POU: whether some CALL calls it. A POU only the entry table calls (a PROGRAM) gains
// nothing from an inline copy and keeps the plain function, whose code GCC allocates better.
std::vector<bool> calledPous(const bc::Module& m) {
  std::vector<bool> called(m.pous.size(), false);
  for (const Instr& ins : m.code)
    if (ins.op == Op::CALL) called[ins.bx()] = true;
  return called;
}

// What every unit knows about every POU. C names come from the POU's name, not its index
// (which a POU added in front shifts), so an edit elsewhere leaves a unit's text alone. Every
// character but letters and digits is written as _XX (hex), so distinct names stay distinct.
struct PouTable {
  // p_NAME: the POU's exported function (a wrapper), s_NAME: its static body in its own unit,
  // i_NAME: a small leaf's inline copy in every unit that calls it
  std::vector<std::string> names;
  std::vector<bool> smallLeaf;
  RegisterPlan plan;

  explicit PouTable(const bc::Module& m) : plan(planRegisters(m)) {
    std::set<std::string> seen;
    const std::vector<bool> called = calledPous(m);
    for (uint32_t p = 0; p < m.pous.size(); ++p) {
      std::string name;
      for (unsigned char ch : m.pous[p].name) {
        if (std::isalnum(ch)) {
          name += static_cast<char>(ch);
          continue;
        }
        char hex[4];
        std::snprintf(hex, sizeof hex, "_%02x", ch);
        name += hex;
      }
      if (!seen.insert(name).second) name += "__" + std::to_string(p);  // hand-built modules may repeat names
      names.push_back(std::move(name));
      smallLeaf.push_back(called[p] && isSmallLeaf(m, m.pous[p]));
    }
  }
  // The registers a small leaf reads before writing them: its inline copy takes them as
  // arguments after `mem`, in this order, instead of loading them from the register stack.
  std::vector<unsigned> leafInputs(uint32_t pou) const {
    std::vector<unsigned> in;
    const RegisterSet& load = plan.pous[pou].loadOnEntry;
    for (unsigned r = 0; r < load.size(); ++r)
      if (load[r]) in.push_back(r);
    return in;
  }
  // What a CALL of `pou` calls in a unit that holds the POUs `own`: the inline copy of a
  // small leaf, the static body of a POU of the unit (which the C compiler may inline, as in a
  // single unit), else the exported function of the POU's unit.
  std::string callee(uint32_t pou, const std::set<uint32_t>& own) const {
    return (smallLeaf[pou] ? "i_" : own.count(pou) ? "s_" : "p_") + names[pou];
  }
  // The register count of `pou` as a CALL in a unit that holds the POUs `own` checks it: a
  // constant of the callee's own unit when it lives in another, so that an edit of the callee
  // that changes its register count recompiles its unit alone.
  std::string registerCount(const bc::Module& m, uint32_t pou, const std::set<uint32_t>& own) const {
    if (smallLeaf[pou] || own.count(pou)) return u64Literal(m.pous[pou].numRegs);
    return "nr_" + names[pou];
  }
};

// The parameters of every POU function. `restrict`: the context is reached only through `c`
// while a POU runs, so the C compiler may keep its fields in registers across stores to the
// memory image.
constexpr std::string_view kParams = "(struct AotContext* restrict c, uint32_t base, uint32_t depth)";
// Functions and constants shared between the units of one shared object, not exported from it.
constexpr std::string_view kHidden = "__attribute__((visibility(\"hidden\"))) ";

class PouWriter {
 public:
  PouWriter(const bc::Module& m, uint32_t pou, const PouTable& table, const std::set<uint32_t>& unit, std::string& out)
      : m_(m), pou_(m.pous[pou]), index_(pou), table_(table), unit_(unit), plan_(table.plan), regs_(table.plan.pous[pou]),
        out_(out) {}

  // The function for the instructions [from, to) of the POU (all of them by default), headed
  // by `head` (linkage and name). A piece that starts later loads every register from the
  // register stack and one that ends early stores them all there and returns 0 (the driver
  // calls the next piece), or -1 after a RET (the POU has returned).
  void write(const std::string& head, uint32_t from = 0, uint32_t to = UINT32_MAX) {
    const bool leaf = table_.smallLeaf[index_];
    const uint32_t begin = pou_.codeStart, end = pou_.codeStart + pou_.codeSize;
    from = std::max(from, begin);
    to = std::min(to, end);
    std::vector<bool> targets(pou_.codeSize, false);
    for (uint32_t pc = from; pc < to; ++pc)
      if (isJump(m_.code[pc].op)) targets[jumpTarget(pc, m_.code[pc]) - begin] = true;

    out_ += head;
    if (leaf) {
      out_ += "(struct AotContext* restrict c, uint32_t base, uint32_t depth, uint8_t* const mem";
      for (unsigned r : table_.leafInputs(index_)) out_ += ", uint64_t in" + std::to_string(r);
      out_ += ") {\n";
    } else {
      out_ += kParams;
      out_ += " {\n  uint8_t* const mem = c->mem;\n";
    }
    out_ += "  uint64_t* const w = c->regs + base;\n";
    out_ += "  uint64_t remaining = c->remaining;\n  int result;\n  (void)depth;\n";
    for (unsigned r = 0; r < pou_.numRegs; ++r)
      out_ += "  uint64_t " + reg(r) +
              (leaf && regs_.loadOnEntry[r]           ? " = in" + std::to_string(r) + ";\n"
               : from > begin || regs_.loadOnEntry[r] ? " = w[" + std::to_string(r) + "];\n"
                                                      : " = 0;\n");
    for (uint32_t pc = from; pc < to; ++pc) {
      if (targets[pc - begin]) out_ += label(pc - begin) + ":;\n";
      out_ += "  ";
      expand(pc, m_.code[pc]);
      out_ += "\n";
    }
    if (to < end) {
      out_ += "  ";
      for (unsigned r = 0; r < pou_.numRegs; ++r) out_ += "w[" + std::to_string(r) + "] = " + reg(r) + "; ";
      out_ += "\n  c->remaining = remaining;\n  return 0;\n";
    }
    // A fault leaves without the write-back: no bytecode reads those registers afterwards.
    out_ += "finish:\n  ";
    for (unsigned r = 0; r < pou_.numRegs; ++r)
      if (regs_.writeBack[r]) out_ += "w[" + std::to_string(r) + "] = " + reg(r) + "; ";
    out_ += "\n  c->remaining = remaining;\n  return ";
    out_ += to < end ? "-1" : "0";
    out_ += ";\nfail:\n  return result;\n}\n\n";
  }

 private:
  // The caller's registers around a CALL at pc: before it, those the callee may read and those
  // read after it; after it, the latter are reloaded (the callee may have changed them).
  void callRegs(uint32_t pc, const Instr& ins, bool load) {
    const RegisterSet& liveAfter = regs_.liveAfterCall[pc - pou_.codeStart];
    const RegisterSet& inputs = plan_.inputs[ins.bx()];
    const bool byValue = table_.smallLeaf[ins.bx()];
    for (uint32_t r = ins.a; r < pou_.numRegs; ++r) {
      const bool calleeReads = !byValue && r - ins.a < inputs.size() && inputs[r - ins.a];
      if (!liveAfter[r] && (load || !calleeReads)) continue;
      const std::string slot = "w[" + std::to_string(r) + "]";
      out_ += load ? reg(r) + " = " + slot + "; " : slot + " = " + reg(r) + "; ";
    }
  }
  // The arguments after (c, base, depth) of a CALL of `pou` at window A: none, or for a small
  // leaf `mem` and its inputs, the caller's registers (those beyond the caller's window from the
  // register stack, where the caller's caller stored them).
  void leafArgs(uint32_t pou, uint32_t a) {
    if (!table_.smallLeaf[pou]) return;
    out_ += ", mem";
    for (unsigned r : table_.leafInputs(pou))
      out_ += ", " + (a + r < pou_.numRegs ? reg(a + r) : "w[" + std::to_string(a + r) + "]");
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

  // Fault pcs are relative to the POU's first instruction, whose index is a constant of the
  // table unit (read on the fault path only): code added to a POU in front leaves this POU's
  // text alone.
  std::string pcText(uint32_t pc) const {
    return "(pc0_" + table_.names[index_] + " + " + std::to_string(pc - pou_.codeStart) + "u)";
  }

  void expand(uint32_t pc, const Instr& ins) {
    if (ins.op == Op::CALLN && !pureNativeName(ins.bx()).empty()) return pureNativeCall(ins);
    const std::string_view text = opcodeSnippet(ins.op);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] != '%' || i + 1 == text.size()) {
        out_ += text[i];
        continue;
      }
      placeholder(text[++i], pc, ins);
    }
  }

  // A CALLN of a pure native: its arguments through a local array, which the C compiler
  // scalarises once it has inlined the function; only r[A] changes, as in the interpreter.
  void pureNativeCall(const Instr& ins) {
    out_ += "{ uint64_t a_[" + std::to_string(nativeArity(ins)) + "]; ";
    nativeArgs(ins, false);
    out_ += reg(ins.a) + " = pureNative_" + std::string(pureNativeName(ins.bx())) + "(a_); }";
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
      case 'p': out_ += pcText(pc); break;
      case 'T': out_ += label(jumpTarget(pc, ins) - pou_.codeStart); break;
      case 'J': if (bc::branchOffset(ins) < 0) out_ += "BUDGET(" + pcText(pc) + ");"; break;
      case 'K': out_ += u64Literal(m_.constants[ins.bx()]); break;
      case 'L': out_ += i64Literal(m_.indexes[ins.c].lo); break;
      case 'N': out_ += i64Literal(m_.indexes[ins.c].count); break;
      case 'Z': out_ += u64Literal(m_.indexes[ins.c].stride); break;
      case 'F': out_ += u64Literal(m_.pous[ins.bx()].frameSize); break;
      case 'G': out_ += u64Literal(m_.pous[ins.bx()].frameTemplate); break;
      case 'R': out_ += table_.registerCount(m_, ins.bx(), unit_); break;
      case 'P': out_ += table_.callee(ins.bx(), unit_); break;
      case 'I': leafArgs(ins.bx(), ins.a); break;
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
  const PouTable& table_;
  const std::set<uint32_t>& unit_;
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


// The definitions every unit starts with: the ABI, the module's memory constants, the helpers
// the native FBs and the pure natives (static inline: a unit compiles only those it uses).
std::string prelude(const bc::Module& m) {
  std::string out = "/* generated by virtcom from bytecode; do not edit */\n#include <stdbool.h>\n#include <stdint.h>\n";
  out += kAbiText;
  out += "\n#define MSZ " + u64Literal(m.memorySize()) + "\n#define GUARD " + u64Literal(bc::Module::kNullGuard) +
         "\n#define STATIC " + u64Literal(m.staticSize) + "\n";
  writeFaultKinds(out);
  out += kPrelude;
  out += kNativeFbAccessors;
  out += kNativeFbCode;
  out += "\n";
  out += kPureNativeCode;
  out += "\n";
  return out;
}

// POUs in module order, cut into units. A unit ends once it holds `limit` instructions or,
// past a quarter of that, after a POU whose name hashes to 0 mod 4; a POU of `limit` or more
// starts a unit of its own. The cuts depend only on the POUs around them, so a POU that grows
// or shrinks moves at most the cuts up to the next name-chosen one.
std::vector<std::vector<uint32_t>> groupPous(const bc::Module& m, uint32_t limit) {
  std::vector<std::vector<uint32_t>> groups(1);
  uint64_t size = 0;
  for (uint32_t p = 0; p < m.pous.size(); ++p) {
    const bc::PouInfo& pou = m.pous[p];
    if (pou.codeSize >= limit && !groups.back().empty()) {
      groups.emplace_back();
      size = 0;
    }
    groups.back().push_back(p);
    size += pou.codeSize;
    const bool nameCut = size >= limit / 4 && hashText(pou.name) % 4 == 0;
    if ((size >= limit || nameCut) && p + 1 < m.pous.size()) {
      groups.emplace_back();
      size = 0;
    }
  }
  return groups;
}

void declarePou(const PouTable& t, uint32_t p, std::string& out) {
  out += std::string(kHidden) + "int p_" + t.names[p] + std::string(kParams) + ";\n";
}

void declareRegisterCount(const PouTable& t, uint32_t p, std::string& out) {
  out += "extern " + std::string(kHidden) + "const uint32_t nr_" + t.names[p] + ";\n";
}

void declarePc0(const PouTable& t, uint32_t p, std::string& out) {
  out += "extern " + std::string(kHidden) + "const uint32_t pc0_" + t.names[p] + ";\n";
}

// A run of a POU's instructions [from, to) that becomes one C function: the whole POU
// (chunk < 0), or one of the `chunks` chunks of a huge one.
struct Piece {
  uint32_t pou, from, to;
  int chunk = -1;
  int chunks = 0;
};

std::string chunkName(const PouTable& t, uint32_t pou, int chunk) {
  return "c_" + t.names[pou] + "_" + std::to_string(chunk);
}

// Where a huge POU is cut into chunks of about `size` instructions: before an instruction no
// jump crosses (ST's top-level statements), so every jump stays inside its chunk. GCC's time
// and memory grow faster than a function's size (docs/performance.md), a chain of chunks of
// bounded size costs time proportional to the POU's.
std::vector<uint32_t> chunkStarts(const bc::Module& m, const bc::PouInfo& p, uint32_t size) {
  std::vector<int> crossing(p.codeSize + 1, 0);  // jumps over the cut before each instruction, as differences
  for (uint32_t pc = p.codeStart; pc < p.codeStart + p.codeSize; ++pc) {
    if (!isJump(m.code[pc].op)) continue;
    const uint32_t target = jumpTarget(pc, m.code[pc]);
    ++crossing[std::min(pc, target) - p.codeStart + 1];
    --crossing[std::max(pc, target) - p.codeStart + 1];
  }
  std::vector<uint32_t> starts{p.codeStart};
  int open = crossing[0];
  for (uint32_t i = 1; i < p.codeSize; ++i) {
    open += crossing[i];
    if (open == 0 && p.codeStart + i - starts.back() >= size && p.codeSize - i >= size / 2) starts.push_back(p.codeStart + i);
  }
  return starts;
}

// The pieces of a group of POUs, in units of at most `limit` instructions: the POUs whole, or
// a huge POU (alone in its group) in chunks spread over several units.
std::vector<std::vector<Piece>> piecesOf(const bc::Module& m, const std::vector<uint32_t>& group, uint32_t limit) {
  const bc::PouInfo& first = m.pous[group.front()];
  std::vector<uint32_t> starts;
  if (group.size() == 1 && first.codeSize > kChunkInstructions) starts = chunkStarts(m, first, kChunkInstructions);
  if (starts.size() < 2) {
    std::vector<Piece> whole;
    for (uint32_t p : group) whole.push_back({p, m.pous[p].codeStart, m.pous[p].codeStart + m.pous[p].codeSize});
    return {whole};
  }
  std::vector<std::vector<Piece>> units(1);
  uint32_t size = 0;
  const auto chunks = static_cast<int>(starts.size());
  for (int k = 0; k < chunks; ++k) {
    const uint32_t to = k + 1 < chunks ? starts[k + 1] : first.codeStart + first.codeSize;
    if (size >= limit) {
      units.emplace_back();
      size = 0;
    }
    units.back().push_back({group.front(), starts[k], to, k, chunks});
    size += to - starts[k];
  }
  return units;
}

// One unit: its pieces, preceded by inline copies of the small leaves they call (a leaf of the
// unit is such a copy too). A whole POU is a static function behind an exported wrapper, so
// within the unit the C compiler sees what it saw when the module was one unit; chunks are
// exported and called in turn by their POU's driver, in the unit of the first chunk.
CUnit writeUnit(const bc::Module& m, const PouTable& t, const std::vector<Piece>& pieces) {
  CUnit unit;
  std::set<uint32_t> own, leaves, external, bodies;
  for (const Piece& piece : pieces) {
    if (piece.chunk <= 0) own.insert(piece.pou);
    bodies.insert(piece.pou);
    unit.largestPou = std::max(unit.largestPou, piece.to - piece.from);
  }
  for (const Piece& piece : pieces) {
    if (t.smallLeaf[piece.pou]) leaves.insert(piece.pou);
    for (uint32_t pc = piece.from; pc < piece.to; ++pc) {
      if (m.code[pc].op != Op::CALL) continue;
      const uint32_t callee = m.code[pc].bx();
      if (t.smallLeaf[callee]) leaves.insert(callee);
      else if (!own.count(callee)) external.insert(callee);
    }
  }
  bodies.insert(leaves.begin(), leaves.end());
  std::string& out = unit.source;
  out = prelude(m);
  for (uint32_t p : external) {
    declarePou(t, p, out);
    declareRegisterCount(t, p, out);
  }
  for (uint32_t p : own)
    if (!t.smallLeaf[p]) out += "static int s_" + t.names[p] + std::string(kParams) + ";\n";
  for (const Piece& piece : pieces)
    for (int k = 0; piece.chunk == 0 && k < piece.chunks; ++k)
      out += std::string(kHidden) + "int " + chunkName(t, piece.pou, k) + std::string(kParams) + ";\n";
  for (uint32_t p : bodies) declarePc0(t, p, out);
  out += "\n";
  for (uint32_t p : leaves)
    PouWriter(m, p, t, own, out).write("static inline __attribute__((always_inline)) int i_" + t.names[p]);
  for (const Piece& piece : pieces) {
    if (t.smallLeaf[piece.pou]) continue;
    PouWriter writer(m, piece.pou, t, own, out);
    if (piece.chunk < 0) writer.write("static int s_" + t.names[piece.pou]);
    else writer.write(std::string(kHidden) + "__attribute__((noinline)) int " + chunkName(t, piece.pou, piece.chunk),
                      piece.from, piece.to);
  }
  for (const Piece& piece : pieces) {
    if (piece.chunk != 0) continue;
    out += "static int s_" + t.names[piece.pou] + std::string(kParams) + " {\n  int r_;\n";
    for (int k = 0; k + 1 < piece.chunks; ++k)
      out += "  if ((r_ = " + chunkName(t, piece.pou, k) + "(c, base, depth))) return r_ < 0 ? 0 : r_;\n";
    out += "  return " + chunkName(t, piece.pou, piece.chunks - 1) + "(c, base, depth);\n}\n";
  }
  for (uint32_t p : own) {
    out += std::string(kHidden) + "const uint32_t nr_" + t.names[p] + " = " + std::to_string(m.pous[p].numRegs) + "u;\n";
    out += std::string(kHidden) + "int p_" + t.names[p] + std::string(kParams) + " { return ";
    if (!t.smallLeaf[p]) {
      out += "s_" + t.names[p] + "(c, base, depth); }\n";
      continue;
    }
    out += "i_" + t.names[p] + "(c, base, depth, c->mem";
    for (unsigned r : t.leafInputs(p)) out += ", c->regs[base + " + std::to_string(r) + "u]";
    out += "); }\n";
  }
  return unit;
}

// The last unit: where each POU starts in the code (for fault pcs) and the exported entry table.
CUnit writeTable(const bc::Module& m, const PouTable& t) {
  CUnit unit;
  std::string& out = unit.source;
  out = "/* generated by virtcom from bytecode; do not edit */\n#include <stdint.h>\n";
  out += kAbiText;
  out += "\n";
  const auto count = static_cast<uint32_t>(m.pous.size());
  for (uint32_t p = 0; p < count; ++p) {
    declarePou(t, p, out);
    out += std::string(kHidden) + "const uint32_t pc0_" + t.names[p] + " = " + std::to_string(m.pous[p].codeStart) + "u;\n";
  }
  out += std::string("const AotEntry ") + kEntriesSymbol + "[] = {";
  for (uint32_t p = 0; p < count; ++p) out += (p ? ", p_" : "p_") + t.names[p];
  out += "};\n";
  out += std::string("const uint32_t ") + kCountSymbol + " = " + std::to_string(count) + "u;\n";
  out += std::string("const uint32_t ") + kAbiSymbol + " = " + std::to_string(vm::kAotAbiVersion) + "u;\n";
  return unit;
}

}  // namespace

std::vector<CUnit> generateCUnits(const bc::Module& m, uint32_t unitInstructions) {
  const PouTable table(m);
  std::vector<CUnit> units;
  const uint32_t limit = std::max(unitInstructions, 1u);
  for (const auto& group : groupPous(m, limit))
    for (const auto& pieces : piecesOf(m, group, limit)) units.push_back(writeUnit(m, table, pieces));
  units.push_back(writeTable(m, table));
  return units;
}

}  // namespace virtcom::aot
