#include "bytecode/variables.hpp"

#include <algorithm>

#include "core/ascii.hpp"

namespace virtcom::bc {

std::vector<NamedVar> listVariables(const Module& m) {
  auto isProgramInstance = [&m](const Symbol& s) {
    return std::any_of(m.programs.begin(), m.programs.end(), [&](const ProgramInstance& p) { return iequalsAscii(p.name, s.name); });
  };
  std::vector<NamedVar> out;
  for (const Symbol& s : m.symbols)
    if (!isProgramInstance(s)) out.push_back({s.name, VarRef{s.type, s.address, s.bit, s.readOnly}});
  for (const ProgramInstance& p : m.programs) {
    if (p.pou >= m.pous.size() || m.pous[p.pou].instanceType >= m.types.size()) continue;
    for (const Field& f : m.types[m.pous[p.pou].instanceType].fields) {
      if (f.hidden) continue;
      uint32_t address = f.absolute ? f.offset : p.address + f.offset;
      int bit = -1;
      if (f.bit >= 0) {
        address += static_cast<uint32_t>(f.bit) / 8;
        bit = f.bit % 8;
      }
      out.push_back({p.name + "." + f.name, VarRef{f.type, address, static_cast<int8_t>(bit), f.readOnly}});
    }
  }
  return out;
}

}  // namespace virtcom::bc
