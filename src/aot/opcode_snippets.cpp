#include "aot/opcode_snippets.hpp"

#include <iterator>

namespace virtcom::aot {

namespace {

using bc::Op;

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

}  // namespace

std::string_view opcodeSnippet(Op op) { return kSnippets[static_cast<size_t>(op)]; }

RegisterAccess registerAccess(Op op) {
  const std::string_view text = opcodeSnippet(op);
  RegisterAccess r;
  bool onlyAssigned = true, anyA = false;
  for (size_t i = 0; i + 1 < text.size(); ++i) {
    if (text[i] != '%') continue;
    const char p = text[++i];
    if (p == 'B') r.readsB = true;
    if (p == 'C') r.readsC = true;
    if (p != 'A') continue;
    anyA = true;
    if (text.substr(i + 1, 3) != " = ") onlyAssigned = false;
  }
  r.writesA = anyA && onlyAssigned;
  r.readsA = anyA && !onlyAssigned;
  return r;
}

}  // namespace virtcom::aot
