// Redundant-load elimination (load_forwarding.hpp). Code generation loads a variable again at
// every use (each statement starts from scratch with its registers), so a loop body reloads its
// FOR variable and the variables it just read; here a forward dataflow over the POU's basic
// blocks tracks which register holds which loaded location, and a repeated load becomes a
// renaming of the register it would have written.
#include "lang/st/codegen/load_forwarding.hpp"

#include <algorithm>
#include <optional>
#include <span>

#include "bytecode/memory_effects.hpp"
#include "bytecode/verifier.hpp"
#include "lang/st/codegen/liveness.hpp"

namespace virtcom::st {

namespace {

using bc::Instr;
using bc::Op;

// A memory range addressed by an instruction: register `base` + offset, or an absolute address.
using Access = bc::MemoryRange;

bool overlaps(const Access& a, const Access& b) {
  return a.offset < uint64_t{b.offset} + b.width && b.offset < uint64_t{a.offset} + a.width;
}
// Whether a store to `to` may change `o`: only a store from the same base register or to an
// absolute address, away from `o`'s range, is known not to (other bases may alias anything).
bool mayClobber(const Access& to, const Access& o) {
  return to.absolute != o.absolute || to.base != o.base || overlaps(to, o);
}

// Register `reg` holds what instruction `key` (its operand A ignored) computes: a load of a
// location, or a pure function of its operands.
struct Fact {
  Instr key;
  uint16_t reg;

  bool operator==(const Fact& o) const { return computes(o.key) && reg == o.reg; }
  bool computes(const Instr& ins) const { return key.op == ins.op && key.b == ins.b && key.c == ins.c; }
};
using Facts = std::vector<Fact>;

// What a register's value is, as far as reading its low bits back from memory goes.
enum class Shape { Unknown, Bool, Zext8, Sext8, Zext16, Sext16, Zext32, Sext32, Float };

// The shape of what instruction `key` computes.
Shape shapeOf(const Instr& key) {
  switch (key.op) {
    case Op::EQ: case Op::NE: case Op::LT_I: case Op::LE_I: case Op::LT_U: case Op::LE_U:
    case Op::EQ_F: case Op::NE_F: case Op::LT_F: case Op::LE_F:
    case Op::EQK: case Op::NEK: case Op::LTK: case Op::LEK: case Op::GTK: case Op::GEK:
    case Op::LNOT: case Op::LD_BIT: return Shape::Bool;
    case Op::LD_U8: case Op::LDA_U8: return Shape::Zext8;
    case Op::LD_I8: case Op::LDA_I8: return Shape::Sext8;
    case Op::LD_U16: case Op::LDA_U16: return Shape::Zext16;
    case Op::LD_I16: case Op::LDA_I16: return Shape::Sext16;
    case Op::LD_U32: case Op::LDA_U32: return Shape::Zext32;
    case Op::LD_I32: case Op::LDA_I32: return Shape::Sext32;
    case Op::ZEXT: return key.c == 8 ? Shape::Zext8 : key.c == 16 ? Shape::Zext16 : key.c == 32 ? Shape::Zext32 : Shape::Unknown;
    case Op::SEXT: return key.c == 8 ? Shape::Sext8 : key.c == 16 ? Shape::Sext16 : key.c == 32 ? Shape::Sext32 : Shape::Unknown;
    // REAL results are exactly a float: ST_F32 then LD_F32 gives them back bit for bit.
    case Op::LD_F32: case Op::LDA_F32: case Op::ADD_F32: case Op::SUB_F32: case Op::MUL_F32: case Op::DIV_F32:
    case Op::RND_F32: return Shape::Float;
    default: return Shape::Unknown;
  }
}

// Whether `load` gives back exactly a register of shape `s` after a store of the same width
// (the store keeps the low bits, the load extends them again).
bool readsBack(Op load, Shape s) {
  using enum Shape;
  switch (load) {
    case Op::LD_U8: case Op::LDA_U8: return s == Bool || s == Zext8;
    case Op::LD_I8: case Op::LDA_I8: return s == Bool || s == Sext8;
    case Op::LD_U16: case Op::LDA_U16: return s == Bool || s == Zext8 || s == Zext16;
    case Op::LD_I16: case Op::LDA_I16: return s == Bool || s == Zext8 || s == Sext8 || s == Sext16;
    case Op::LD_U32: case Op::LDA_U32: return s == Bool || s == Zext8 || s == Zext16 || s == Zext32;
    case Op::LD_I32: case Op::LDA_I32:
      return s == Bool || s == Zext8 || s == Sext8 || s == Zext16 || s == Sext16 || s == Sext32;
    case Op::LD_F32: case Op::LDA_F32: return s == Float;
    case Op::LD_64: case Op::LDA_64: return true;  // all 64 bits
    default: return false;
  }
}

// The loads of the width a register store writes (ST_x, STA_x); empty for other instructions.
std::vector<Op> loadsOfStoreWidth(Op store) {
  switch (store) {
    case Op::ST_8: return {Op::LD_U8, Op::LD_I8};
    case Op::ST_16: return {Op::LD_U16, Op::LD_I16};
    case Op::ST_32: return {Op::LD_U32, Op::LD_I32};
    case Op::ST_64: return {Op::LD_64};
    case Op::ST_F32: return {Op::LD_F32};
    case Op::STA_8: return {Op::LDA_U8, Op::LDA_I8};
    case Op::STA_16: return {Op::LDA_U16, Op::LDA_I16};
    case Op::STA_32: return {Op::LDA_U32, Op::LDA_I32};
    case Op::STA_64: return {Op::LDA_64};
    case Op::STA_F32: return {Op::LDA_F32};
    default: return {};
  }
}

// The shape of register `reg` by what the facts say it holds; nullopt when no fact names it.
// A register without facts may be one whose writer is being removed (Forwarder::run follows the
// code as it was): in the rewritten code it still holds its older value, its readers read the
// register that served the removed instruction. Only a register with a fact was written by an
// instruction that stays (a removed one was served, and a served instruction adds no fact).
std::optional<Shape> shapeOfRegister(const Facts& facts, uint16_t reg) {
  std::optional<Shape> shape;
  for (const Fact& f : facts)
    if (f.reg == reg && (!shape || *shape == Shape::Unknown)) shape = shapeOf(f.key);
  return shape;
}

// The facts a store of register A (of `shape`) adds: A holds what each load of the stored
// location that reads it back exactly would give (a REAL reloaded after its store, a BOOL
// after `x := a < b`, a WORD loaded and stored).
void addStoredFacts(const Instr& store, Shape shape, Facts& facts) {
  for (const Op load : loadsOfStoreWidth(store.op)) {
    if (!readsBack(load, shape)) continue;
    Instr key = store;  // the location: B and C (register + offset), or Bx (absolute)
    key.op = load;
    facts.push_back({key, store.a});
  }
}

// Instructions whose result depends on their operands alone (registers, immediates, constants):
// computed again on the same operands, they give the same value, or the same fault, which the
// first one would already have raised. SYSTIME is not one: it counts its reads.
bool pure(Op op) {
  switch (op) {
    case Op::LDI: case Op::LDK: case Op::INDEX:
    case Op::ADD: case Op::SUB: case Op::MUL: case Op::DIV_I: case Op::MOD_I: case Op::DIV_U: case Op::MOD_U:
    case Op::ADDI: case Op::DIVK: case Op::MODK: case Op::NEG: case Op::SEXT: case Op::ZEXT:
    case Op::BAND: case Op::BOR: case Op::BXOR: case Op::BNOT: case Op::LNOT: case Op::SHL: case Op::SHR:
    case Op::EQ: case Op::NE: case Op::LT_I: case Op::LE_I: case Op::LT_U: case Op::LE_U:
    case Op::EQ_F: case Op::NE_F: case Op::LT_F: case Op::LE_F:
    case Op::EQK: case Op::NEK: case Op::LTK: case Op::LEK: case Op::GTK: case Op::GEK:
    case Op::ADD_F: case Op::SUB_F: case Op::MUL_F: case Op::DIV_F:
    case Op::ADD_F32: case Op::SUB_F32: case Op::MUL_F32: case Op::DIV_F32: case Op::NEG_F: case Op::RND_F32:
    case Op::I2F: case Op::U2F: case Op::F2I: case Op::F2I_TRUNC: case Op::F2U: return true;
    default: return false;
  }
}

// Whether `ins` reads register `reg` through operand B or C (not A: forwarded instructions only
// write A).
bool readsBC(const Instr& ins, uint16_t reg) {
  if (bc::opFormat(ins.op) != bc::Format::ABC) return false;
  const bc::OperandRoles roles = bc::operandRoles(ins.op);
  return (roles.b == bc::Operand::Reg && ins.b == reg) || (roles.c == bc::Operand::Reg && ins.c == reg);
}

// Whether `shape` is already what extending its low `bits` bits gives (signed: SEXT; else ZEXT).
bool extendedAlready(Shape shape, uint16_t bits, bool isSigned) {
  using enum Shape;
  const auto narrowest = [](Shape s) -> uint16_t {
    switch (s) {
      case Bool: return 1;
      case Zext8: case Sext8: return 8;
      case Zext16: case Sext16: return 16;
      case Zext32: case Sext32: return 32;
      default: return 64;
    }
  };
  const bool zext = shape == Bool || shape == Zext8 || shape == Zext16 || shape == Zext32;
  const bool sext = shape == Sext8 || shape == Sext16 || shape == Sext32;
  // A zero-extended value narrower than `bits` is its own sign-extension too.
  if (isSigned) return (sext && narrowest(shape) <= bits) || (zext && narrowest(shape) < bits);
  return zext && narrowest(shape) <= bits;
}

// The register whose value `ins` copies unchanged: B of a MOV, and of a SEXT/ZEXT of a register
// whose value is already in that form (a loaded INT sign-extended to 16 bits again); nullopt
// for other instructions.
std::optional<uint16_t> copiedRegister(const Instr& ins, const Facts& facts) {
  if (ins.op == Op::MOV) return ins.b;
  if (ins.op != Op::SEXT && ins.op != Op::ZEXT) return std::nullopt;
  const std::optional<Shape> shape = shapeOfRegister(facts, ins.b);
  if (shape && extendedAlready(*shape, ins.c, ins.op == Op::SEXT)) return ins.b;
  return std::nullopt;
}

// The fact that a register already holds what `ins` computes; null if none.
const Fact* holder(const Facts& facts, const Instr& ins) {
  if (!pure(ins.op) && !bc::loadedRange(ins)) return nullptr;
  for (const Fact& f : facts)
    if (f.computes(ins)) return &f;
  return nullptr;
}

// The range `width` bytes at `offset` from `base` may address when `base` holds the address of
// an element of a one-dimensional array (ADD base, rb, ri with ri = INDEX(.., d), as code
// generation addresses a[i]): any element of the array, relative to rb; nullopt otherwise.
std::optional<Access> elementRegion(uint16_t base, int64_t offset, uint32_t width, const Facts& facts,
                                    const std::vector<bc::IndexDesc>& indexes) {
  for (const Fact& sum : facts) {
    if (sum.reg != base || sum.key.op != Op::ADD) continue;
    for (const Fact& index : facts)
      if (index.reg == sum.key.c && index.key.op == Op::INDEX && index.key.c < indexes.size()) {
        const uint64_t span = indexes[index.key.c].lastOffset() + width;
        if (span > UINT32_MAX || offset < 0 || offset > UINT32_MAX) return std::nullopt;
        return Access{false, sum.key.b, static_cast<uint32_t>(offset), static_cast<uint32_t>(span)};
      }
  }
  return std::nullopt;
}

// What `at` may address, seen from a known base: the array region of its element (above),
// also when the base is an element's address plus a constant (ADDI: a member of an FB instance
// in an array, as a call of counters[i] addresses it); the same bytes from the ADDI's base when
// the base is a member's address (the instance of a call of fb, scalar); `at` itself otherwise.
// So a store into an array, or into the instance of an FB called, no longer hides every other
// variable of the instance.
Access region(const Access& at, const Facts& facts, const std::vector<bc::IndexDesc>& indexes) {
  if (at.absolute) return at;
  if (const std::optional<Access> element = elementRegion(at.base, at.offset, at.width, facts, indexes)) return *element;
  for (const Fact& member : facts) {
    if (member.reg != at.base || member.key.op != Op::ADDI) continue;
    const int64_t offset = int64_t{at.offset} + static_cast<int16_t>(member.key.c);
    if (const std::optional<Access> element = elementRegion(member.key.b, offset, at.width, facts, indexes)) return *element;
    if (offset >= 0 && offset <= UINT32_MAX) return Access{false, member.key.b, static_cast<uint32_t>(offset), at.width};
  }
  return at;
}

// The module's array shapes (INDEX) and what its POUs may write when called: what the facts of
// one POU's code are checked against.
class Effects {
 public:
  explicit Effects(const bc::Module& m) : m_(m), reach_(m.pous.size()) {}
  const std::vector<bc::IndexDesc>& indexes() const { return m_.indexes; }
  // bc::thisWriteReach of POU `pou`, worked out once.
  std::optional<uint64_t> thisWriteReach(uint32_t pou) const {
    if (pou >= reach_.size()) return std::nullopt;
    if (!reach_[pou]) reach_[pou] = bc::thisWriteReach(m_, m_.pous[pou]);
    return *reach_[pou];
  }

 private:
  const bc::Module& m_;
  mutable std::vector<std::optional<std::optional<uint64_t>>> reach_;  // a cache
};

// Drops the facts of loads whose location `lost` says may have changed. Locations are resolved
// (region) with all facts still there.
template <typename Lost>
void dropLoads(Facts& facts, const std::vector<bc::IndexDesc>& indexes, Lost lost) {
  Facts kept;
  for (const Fact& f : facts) {
    const std::optional<Access> at = bc::loadedRange(f.key);
    if (!at || !lost(region(*at, facts, indexes))) kept.push_back(f);
  }
  facts = std::move(kept);
}

// The index in `before` of the last instruction that writes register `reg`, or nullopt.
std::optional<size_t> lastWrite(std::span<const Instr> before, uint16_t reg) {
  for (size_t k = before.size(); k-- > 0;)
    if (writesRegister(before[k], reg)) return k;
  return std::nullopt;
}

// What a CALL (at the end of `before`, the instructions of its block before it) may write in
// memory besides the stack above its caller's frame: `reach` bytes past the this it passes, as
// far as the facts place it (empty when nothing); nullopt when it may write anything else. Exact
// for code as generated: the ENTER of the callee's frame into A, then MOV A + 1, rX (rX
// unchanged since) for a callee that writes its instance.
std::optional<std::optional<Access>> callWrites(const Instr& call, std::span<const Instr> before, const Facts& facts,
                                                const Effects& effects) {
  const std::optional<uint64_t> reach = effects.thisWriteReach(call.bx());
  const std::optional<size_t> enter = lastWrite(before, call.a);
  if (!reach || !enter || before[*enter].op != Op::ENTER || before[*enter].bx() != call.bx()) return std::nullopt;
  if (*reach == 0) return std::optional<Access>{};
  const std::optional<size_t> self = lastWrite(before, call.a + 1);
  if (!self || before[*self].op != Op::MOV || *reach > UINT32_MAX) return std::nullopt;
  const uint16_t source = before[*self].b;
  if (lastWrite(before.subspan(*self + 1), source)) return std::nullopt;
  return region(Access{false, source, 0, static_cast<uint32_t>(*reach)}, facts, effects.indexes());
}

// Whether `at` is a location of the running POU's frame or instance (fp and this: r0 and r1,
// which lie below the stack's top) or a global (absolute, in static memory).
bool callersOwn(const Access& at) { return at.absolute || at.base < 2; }

// Whether register `reg` holds a frame the running POU set up for a callee (ENTER): an address
// on the stack above its own frame, which none of its own locations overlap.
bool holdsFrame(const Facts& facts, uint16_t reg) {
  return std::any_of(facts.begin(), facts.end(), [&](const Fact& f) { return f.reg == reg && f.key.op == Op::ENTER; });
}

// The memory effects of `ins` on the facts (its register write is the caller's to apply).
// ENTER writes only the stack above the running POU's frame, and a call whose callee writes
// besides only its instance (callWrites) leaves the loads of the caller's own locations
// (callersOwn) that the instance does not overlap; so does a store into a callee's frame (its
// arguments). Other calls, copies and coverage counters may write anything: every load goes,
// the pure facts stay.
void applyStores(const Instr& ins, std::span<const Instr> before, Facts& facts, const Effects& effects) {
  if (ins.op == Op::ENTER) {
    dropLoads(facts, effects.indexes(), [&](const Access& at) { return !callersOwn(at); });
  } else if (ins.op == Op::CALL) {
    const std::optional<std::optional<Access>> written = callWrites(ins, before, facts, effects);
    dropLoads(facts, effects.indexes(), [&](const Access& at) {
      return !written || !callersOwn(at) || (*written && mayClobber(**written, at));
    });
  } else if (bc::writesBeyondRanges(ins.op)) {
    std::erase_if(facts, [](const Fact& f) { return bc::loadedRange(f.key).has_value(); });
  } else if (const std::optional<Access> store = bc::storedRange(ins)) {
    // The stored register's shape and the store's region are resolved before its loads go.
    const Access to = region(*store, facts, effects.indexes());
    const std::optional<Shape> stored = shapeOfRegister(facts, ins.a);
    const bool toStack = !to.absolute && holdsFrame(facts, to.base);  // a callee's argument
    dropLoads(facts, effects.indexes(), [&](const Access& at) { return mayClobber(to, at) && !(toStack && callersOwn(at)); });
    // A store of a register nothing is known about adds nothing: it may be stale (transfer).
    if (stored) addStoredFacts(ins, *stored, facts);
  }
}

// The facts after `ins`, the end of `before` (the instructions of its block before it). A
// repeated load keeps the register that already holds the location, whether or not the load is
// then removed, so the facts hold for the code before and after.
void transfer(const Instr& ins, std::span<const Instr> before, Facts& facts, const Effects& effects) {
  const Fact* held = holder(facts, ins);
  if (held && held->reg == ins.a) return;  // it writes the value its register already has
  // Forwarder::run judges a copy on its renamed operand; here, on the code as generated, an
  // operand without facts may be a removed load's register that run renamed and found to be a
  // copy: such an extension adds no fact either.
  const bool extension = ins.op == Op::SEXT || ins.op == Op::ZEXT;
  const bool copied = ins.op == Op::MOV || (extension && (!shapeOfRegister(facts, ins.b) || copiedRegister(ins, facts)));
  applyStores(ins, before, facts, effects);
  if (const std::optional<RegisterWrite> w = registerWrite(ins)) {
    const auto hit = [&](uint16_t reg) { return reg == w->reg || (w->andAbove && reg > w->reg); };
    std::erase_if(facts, [&](const Fact& f) {
      if (hit(f.reg)) return true;
      if (bc::opFormat(f.key.op) != bc::Format::ABC) return false;
      const bc::OperandRoles roles = bc::operandRoles(f.key.op);
      return (roles.b == bc::Operand::Reg && hit(f.key.b)) || (roles.c == bc::Operand::Reg && hit(f.key.c));
    });
  }
  // A result that overwrote one of its own operands is no longer what the operands compute. A
  // copy (removed, or kept where renaming failed) adds nothing either: once removed, its register
  // is not written, and a later equal copy must not be served from it.
  if (!held && !copied && (pure(ins.op) || bc::loadedRange(ins)) && !readsBC(ins, ins.a)) facts.push_back({ins, ins.a});
  if (ins.op == Op::ENTER) facts.push_back({ins, ins.a});  // never served (holder): for holdsFrame
}

Facts meet(const Facts& a, const Facts& b) {
  Facts out;
  for (const Fact& f : a)
    if (std::find(b.begin(), b.end(), f) != b.end()) out.push_back(f);
  return out;
}

class Forwarder {
 public:
  Forwarder(bc::Module& m, uint32_t begin, uint32_t end, uint16_t numRegs)
      : code_(m.code), effects_(m), begin_(begin), n_(end - begin), numRegs_(numRegs), live_(m.code, begin, end, numRegs),
        leader_(n_, false), removed_(n_, false) {}

  std::vector<bool> run() {
    findBlocks();
    const std::vector<std::optional<Facts>> in = blockEntryFacts();
    // The facts are followed on the code as it was, exactly as blockEntryFacts did: the entry
    // facts of the next blocks say which register holds what in that code. Were a removed load
    // to keep the facts of the register it wrote, a later load into another register could be
    // served from the older one and removed, while the next block still counts on that other
    // register (issue 17: `done` in a job-list program read from a register never written).
    const std::vector<Instr> original(code_.begin() + begin_, code_.begin() + begin_ + n_);
    for (uint32_t k = 0; k < n_; ++k) {
      if (!leader_[k] || !in[k]) continue;
      Facts facts = *in[k];
      for (uint32_t j = k; j < n_ && (j == k || !leader_[j]); ++j) {
        if (const Fact* held = holder(facts, original[j])) removed_[j] = rename(j, held->reg);
        // A copy is judged on its renamed operand: its original one may be a removed load's.
        else if (const std::optional<uint16_t> copied = copiedRegister(code_[begin_ + j], facts)) removed_[j] = rename(j, *copied);
        transfer(original[j], std::span(original).subspan(k, j - k), facts, effects_);
      }
    }
    return removed_;
  }

 private:
  bool endsBlock(uint32_t k) const {
    const Op op = code_[begin_ + k].op;
    return bc::isBranch(op) || op == Op::RET || op == Op::TRAP;
  }
  bool fallsThrough(uint32_t k) const {
    const Op op = code_[begin_ + k].op;
    return op != Op::JMP && op != Op::RET && op != Op::TRAP && k + 1 < n_;
  }
  uint32_t targetOf(uint32_t k) const {
    return static_cast<uint32_t>(bc::branchTarget(begin_ + k, code_[begin_ + k]) - begin_);
  }

  void findBlocks() {
    leader_[0] = true;
    for (uint32_t k = 0; k < n_; ++k) {
      if (bc::isBranch(code_[begin_ + k].op)) leader_[targetOf(k)] = true;
      if (endsBlock(k) && k + 1 < n_) leader_[k + 1] = true;
    }
  }

  // The facts on entry of each block (indexed by its leader), nullopt where none reaches it:
  // forward dataflow from the POU's entry with nothing known, meeting by intersection.
  std::vector<std::optional<Facts>> blockEntryFacts() const {
    std::vector<std::optional<Facts>> in(n_);
    in[0] = Facts{};
    const auto flowInto = [&](uint32_t to, const Facts& facts, bool& changed) {
      std::optional<Facts> next = in[to] ? meet(*in[to], facts) : facts;
      if (to == 0) next = Facts{};
      if (next != in[to]) {
        in[to] = std::move(next);
        changed = true;
      }
    };
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t k = 0; k < n_; ++k) {
        if (!leader_[k] || !in[k]) continue;
        Facts facts = *in[k];
        uint32_t j = k;
        for (;; ++j) {
          transfer(code_[begin_ + j], std::span(code_).subspan(begin_ + k, j - k), facts, effects_);
          if (endsBlock(j) || j + 1 == n_ || leader_[j + 1]) break;
        }
        if (bc::isBranch(code_[begin_ + j].op)) flowInto(targetOf(j), facts, changed);
        if (fallsThrough(j)) flowInto(j + 1, facts, changed);
      }
    }
    return in;
  }

  // Replaces the load at k (into rY) by `holding` in the reads that follow, up to the next write
  // of rY; false (nothing changed) if rY is read by a call window, after `holding` is written,
  // or after the end of the block.
  bool rename(uint32_t k, uint16_t holding) {
    const uint16_t y = code_[begin_ + k].a;
    if (y == holding) return true;
    std::vector<uint16_t*> uses;
    bool clobbered = false;
    for (uint32_t j = k + 1; j < n_; ++j) {
      if (leader_[j]) {  // fell through into the next block
        if (live_.liveBefore(begin_ + j, y)) return false;
        break;
      }
      Instr& ins = code_[begin_ + j];
      const RegisterReads reads = registerReads(ins, numRegs_);
      if (y >= reads.windowFrom && y < reads.windowTo) return false;
      for (int i = 0; i < reads.count; ++i)
        if (*reads.regs[i] == y) {
          if (clobbered) return false;
          uses.push_back(reads.regs[i]);
        }
      if (writesRegister(ins, y)) break;
      clobbered |= writesRegister(ins, holding);
      if (endsBlock(j)) {
        if (bc::isBranch(ins.op) && live_.liveBefore(begin_ + targetOf(j), y)) return false;
        if (fallsThrough(j) && live_.liveBefore(begin_ + j + 1, y)) return false;
        break;
      }
    }
    for (uint16_t* use : uses) *use = holding;
    return true;
  }

  std::vector<Instr>& code_;
  Effects effects_;
  uint32_t begin_, n_;
  uint16_t numRegs_;
  Liveness live_;
  std::vector<bool> leader_;
  std::vector<bool> removed_;
};

}  // namespace

std::vector<bool> forwardLoads(bc::Module& m, uint32_t begin, uint32_t end, uint16_t numRegs) {
  return Forwarder(m, begin, end, numRegs).run();
}

}  // namespace virtcom::st
