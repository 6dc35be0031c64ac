#pragma once
// Hand-assembles small modules for the VM tests: static memory, POUs, code and line entries.
#include <cstdint>
#include <cstring>
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::test {

using bc::Instr;
using bc::Op;

inline Instr abc(Op op, uint16_t a = 0, uint16_t b = 0, uint16_t c = 0) { return Instr::abc(op, a, b, c); }
inline Instr abx(Op op, uint16_t a, uint32_t bx) { return Instr::abx(op, a, bx); }
inline Instr asbx(Op op, uint16_t a, int32_t sbx) { return Instr::asbx(op, a, sbx); }

class ModuleBuilder {
 public:
  explicit ModuleBuilder(uint32_t staticSize = 1024) {
    m.staticSize = staticSize;
    m.initialImage.assign(staticSize, 0);
    m.files = {"MAIN.st", "FB_x.st"};
    m.stackSize = 4096;
  }

  // Starts a POU at the current end of code; following emits belong to it.
  uint32_t beginPou(std::string name, uint16_t numRegs, uint32_t frameSize = 0,
                    uint32_t frameTemplate = 0, bc::PouKind kind = bc::PouKind::Function) {
    bc::PouInfo p;
    p.name = std::move(name);
    p.kind = kind;
    p.codeStart = static_cast<uint32_t>(m.code.size());
    p.numRegs = numRegs;
    p.frameSize = frameSize;
    p.frameTemplate = frameTemplate;
    m.pous.push_back(p);
    return static_cast<uint32_t>(m.pous.size() - 1);
  }

  // Appends an instruction to the current POU; line > 0 adds a line-table entry.
  uint32_t emit(Instr ins, uint32_t line = 0, uint32_t col = 1, uint32_t file = 0) {
    const auto pc = static_cast<uint32_t>(m.code.size());
    m.code.push_back(ins);
    m.pous.back().codeSize++;
    if (line) m.lines.push_back({pc, SourceLocation{file, line, col}});
    return pc;
  }

  uint32_t constant(uint64_t v) {
    m.constants.push_back(v);
    return static_cast<uint32_t>(m.constants.size() - 1);
  }

  template <typename T>
  void poke(uint32_t addr, T v) { std::memcpy(m.initialImage.data() + addr, &v, sizeof v); }
  void pokeString(uint32_t addr, const char* s) { std::memcpy(m.initialImage.data() + addr, s, std::strlen(s) + 1); }

  uint32_t pc() const { return static_cast<uint32_t>(m.code.size()); }

  bc::Module m;
};

}  // namespace virtcom::test
