// Redundant-load elimination (load_forwarding.hpp). Code generation loads a variable again at
// every use (each statement starts from scratch with its registers), so a loop body reloads its
// FOR variable and the variables it just read; here a forward dataflow over the POU's basic
// blocks tracks which register holds which loaded location, and a repeated load becomes a
// renaming of the register it would have written.
#include "lang/st/codegen/load_forwarding.hpp"

#include <algorithm>
#include <optional>

#include "bytecode/verifier.hpp"
#include "lang/st/codegen/liveness.hpp"

namespace virtcom::st {

namespace {

using bc::Instr;
using bc::Op;

// A memory range addressed by an instruction: register `base` + offset, or an absolute address.
struct Access {
  bool absolute = false;
  uint16_t base = 0;
  uint32_t offset = 0;
  uint32_t width = 0;

  bool same(const Access& o) const {
    return absolute == o.absolute && base == o.base && offset == o.offset && width == o.width;
  }
  bool overlaps(const Access& o) const { return offset < o.offset + o.width && o.offset < offset + width; }
  // Whether a store to `this` may change `o`: only a store from the same base register or to an
  // absolute address, away from `o`'s range, is known not to (other bases may alias anything).
  bool mayClobber(const Access& o) const { return absolute != o.absolute || base != o.base || overlaps(o); }
};

// Register `reg` holds what load `op` of `at` reads.
struct Fact {
  Op op;
  Access at;
  uint16_t reg;

  bool operator==(const Fact& o) const {
    return op == o.op && at.same(o.at) && reg == o.reg;
  }
};
using Facts = std::vector<Fact>;

uint32_t accessWidth(Op op) {
  switch (op) {
    case Op::LD_I8: case Op::LD_U8: case Op::ST_8: case Op::STK_8: case Op::ST_BIT: return 1;
    case Op::LD_I16: case Op::LD_U16: case Op::ST_16: case Op::STK_16: return 2;
    case Op::LD_I32: case Op::LD_U32: case Op::LD_F32: case Op::ST_32: case Op::STK_32: case Op::ST_F32: return 4;
    case Op::LD_64: case Op::ST_64: case Op::STK_64: return 8;
    default: return bc::operandRoles(op).width;  // the absolute forms
  }
}

// The location a plain load reads (LD_BIT excluded: it is no whole location); nullopt otherwise.
std::optional<Access> loadOf(const Instr& ins) {
  switch (ins.op) {
    case Op::LD_I8: case Op::LD_U8: case Op::LD_I16: case Op::LD_U16: case Op::LD_I32: case Op::LD_U32:
    case Op::LD_64: case Op::LD_F32:
      return Access{false, ins.b, ins.c, accessWidth(ins.op)};
    case Op::LDA_I8: case Op::LDA_U8: case Op::LDA_I16: case Op::LDA_U16: case Op::LDA_I32: case Op::LDA_U32:
    case Op::LDA_64: case Op::LDA_F32:
      return Access{true, 0, ins.bx(), accessWidth(ins.op)};
    default: return std::nullopt;
  }
}

// The location a store writes; nullopt for instructions that store nothing.
std::optional<Access> storeOf(const Instr& ins) {
  switch (ins.op) {
    case Op::ST_8: case Op::ST_16: case Op::ST_32: case Op::ST_64: case Op::ST_F32:
    case Op::STK_8: case Op::STK_16: case Op::STK_32: case Op::STK_64:
      return Access{false, ins.b, ins.c, accessWidth(ins.op)};
    case Op::ST_BIT: return Access{false, ins.b, 0, 1};
    case Op::STA_8: case Op::STA_16: case Op::STA_32: case Op::STA_64: case Op::STA_F32:
      return Access{true, 0, ins.bx(), accessWidth(ins.op)};
    default: return std::nullopt;
  }
}

// Instructions whose memory effects are not one store: copies, calls (the callee or native may
// write anything), frame set-up, coverage counters, and the ends of the POU.
bool clobbersMemory(Op op) {
  switch (op) {
    case Op::COPY: case Op::CALL: case Op::CALLN: case Op::CALLFB: case Op::ENTER: case Op::COVER:
    case Op::RET: case Op::TRAP: return true;
    default: return false;
  }
}

// The lowest register `ins` writes and whether it writes every register from there up (a call's
// window); nullopt if it writes none.
struct Written {
  uint16_t reg;
  bool andAbove;
};
std::optional<Written> written(const Instr& ins) {
  if (ins.op == Op::CALL || ins.op == Op::CALLN) return Written{ins.a, true};
  if (bc::writesOnlyA(ins.op)) return Written{ins.a, false};
  return std::nullopt;
}
bool writes(const Instr& ins, uint16_t reg) {
  const std::optional<Written> w = written(ins);
  return w && (reg == w->reg || (w->andAbove && reg > w->reg));
}

// The registers `ins` reads, as pointers into it (to rename them); `window` is set when it also
// reads a register range (CALL from A up, CALLN A .. A + arity - 1) that cannot be renamed.
struct Reads {
  uint16_t* regs[3] = {};
  int count = 0;
  uint32_t windowFrom = 0, windowTo = 0;  // [from, to)
};
Reads readsOf(Instr& ins, uint16_t numRegs) {
  Reads r;
  const bc::OperandRoles roles = bc::operandRoles(ins.op);
  if (ins.op == Op::CALL) {
    r.windowFrom = ins.a;
    r.windowTo = numRegs;
    return r;
  }
  if (ins.op == Op::CALLN) {
    r.windowFrom = ins.a;
    r.windowTo = ins.a + bc::nativeArity(static_cast<bc::Native>(ins.bx()));
    return r;
  }
  if (roles.a == bc::Operand::Reg && !bc::writesOnlyA(ins.op)) r.regs[r.count++] = &ins.a;
  if (bc::opFormat(ins.op) == bc::Format::ABC) {
    if (roles.b == bc::Operand::Reg) r.regs[r.count++] = &ins.b;
    if (roles.c == bc::Operand::Reg) r.regs[r.count++] = &ins.c;
  }
  return r;
}

const Fact* holder(const Facts& facts, Op op, const Access& at) {
  for (const Fact& f : facts)
    if (f.op == op && f.at.same(at)) return &f;
  return nullptr;
}

// The facts after `ins`. A repeated load keeps the register that already holds the location,
// whether or not the load is then removed, so the facts hold for the code before and after.
void transfer(const Instr& ins, Facts& facts) {
  const std::optional<Access> load = loadOf(ins);
  const Fact* held = load ? holder(facts, ins.op, *load) : nullptr;
  if (held && held->reg == ins.a) return;  // the load writes the value its register already has
  if (clobbersMemory(ins.op)) facts.clear();
  if (const std::optional<Access> store = storeOf(ins))
    std::erase_if(facts, [&](const Fact& f) { return store->mayClobber(f.at); });
  if (const std::optional<Written> w = written(ins)) {
    const auto hit = [&](uint16_t reg) { return reg == w->reg || (w->andAbove && reg > w->reg); };
    std::erase_if(facts, [&](const Fact& f) { return hit(f.reg) || (!f.at.absolute && hit(f.at.base)); });
  }
  if (load && !held && (load->absolute || load->base != ins.a)) facts.push_back({ins.op, *load, ins.a});
}

Facts meet(const Facts& a, const Facts& b) {
  Facts out;
  for (const Fact& f : a)
    if (std::find(b.begin(), b.end(), f) != b.end()) out.push_back(f);
  return out;
}

class Forwarder {
 public:
  Forwarder(std::vector<Instr>& code, uint32_t begin, uint32_t end, uint16_t numRegs)
      : code_(code), begin_(begin), n_(end - begin), numRegs_(numRegs), live_(code, begin, end, numRegs),
        leader_(n_, false), removed_(n_, false) {}

  std::vector<bool> run() {
    findBlocks();
    const std::vector<std::optional<Facts>> in = blockEntryFacts();
    for (uint32_t k = 0; k < n_; ++k) {
      if (!leader_[k] || !in[k]) continue;
      Facts facts = *in[k];
      for (uint32_t j = k; j < n_ && (j == k || !leader_[j]); ++j) {
        const Instr& ins = code_[begin_ + j];
        if (const std::optional<Access> load = loadOf(ins))
          if (const Fact* held = holder(facts, ins.op, *load)) removed_[j] = rename(j, held->reg);
        transfer(ins, facts);
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
          transfer(code_[begin_ + j], facts);
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
      const Reads reads = readsOf(ins, numRegs_);
      if (y >= reads.windowFrom && y < reads.windowTo) return false;
      for (int i = 0; i < reads.count; ++i)
        if (*reads.regs[i] == y) {
          if (clobbered) return false;
          uses.push_back(reads.regs[i]);
        }
      if (writes(ins, y)) break;
      clobbered |= writes(ins, holding);
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
  uint32_t begin_, n_;
  uint16_t numRegs_;
  Liveness live_;
  std::vector<bool> leader_;
  std::vector<bool> removed_;
};

}  // namespace

std::vector<bool> forwardLoads(std::vector<Instr>& code, uint32_t begin, uint32_t end, uint16_t numRegs) {
  return Forwarder(code, begin, end, numRegs).run();
}

}  // namespace virtcom::st
