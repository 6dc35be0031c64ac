#include "bytecode/module.hpp"

#include <algorithm>
#include <string>

#include "core/ascii.hpp"

namespace virtcom::bc {

SourceLocation Module::locationOf(uint32_t pc) const {
  // The last entry with entry.pc <= pc, as long as it belongs to the same POU.
  auto it = std::upper_bound(lines.begin(), lines.end(), pc,
                             [](uint32_t value, const LineEntry& e) { return value < e.pc; });
  if (it == lines.begin()) return {};
  --it;
  const uint32_t pou = pouAt(pc);
  if (pou != kNoPou && it->pc < pous[pou].codeStart) return {};
  return it->loc;
}

uint32_t Module::pouAt(uint32_t pc) const {
  // POUs are usually laid out in order, but nothing requires it: a linear scan is simple and
  // this is not on the scan path.
  for (uint32_t i = 0; i < pous.size(); ++i)
    if (pc >= pous[i].codeStart && pc - pous[i].codeStart < pous[i].codeSize) return i;
  return kNoPou;
}

namespace {

bool isIdentChar(char c) { return isAsciiLetter(c) || isAsciiDigit(c) || c == '_'; }

// A position in a path while it is being resolved.
struct Cursor {
  TypeId type = kNoType;
  uint64_t address = 0;
  int bit = -1;
  bool readOnly = false;
};

// The symbol (or program instance) whose name is the longest prefix of path ending at a
// separator; sets `used` to the prefix length. A path that matches nothing may still name a
// global by its short name ("x" for "GVL.x") when exactly one symbol has that suffix.
std::optional<Cursor> findRoot(const Module& m, std::string_view path, size_t& used) {
  std::optional<Cursor> best;
  size_t bestLen = 0;
  auto consider = [&](std::string_view name, TypeId type, uint32_t address, bool readOnly, int bit) {
    if (name.size() <= bestLen || name.size() > path.size()) return;
    if (!iequalsAscii(path.substr(0, name.size()), name)) return;
    if (name.size() < path.size() && path[name.size()] != '.' && path[name.size()] != '[') return;
    best = Cursor{type, address, bit, readOnly};
    bestLen = name.size();
  };
  for (const Symbol& s : m.symbols) consider(s.name, s.type, s.address, s.readOnly, s.bit);
  for (const ProgramInstance& p : m.programs)
    if (p.pou < m.pous.size()) consider(p.name, m.pous[p.pou].instanceType, p.address, false, -1);
  if (best) {
    used = bestLen;
    return best;
  }
  size_t head = 0;
  while (head < path.size() && isIdentChar(path[head])) ++head;
  const std::string_view shortName = path.substr(0, head);
  const Symbol* unique = nullptr;
  for (const Symbol& s : m.symbols) {
    const size_t dot = s.name.rfind('.');
    if (dot == std::string::npos || !iequalsAscii(std::string_view(s.name).substr(dot + 1), shortName)) continue;
    if (unique) return std::nullopt;  // ambiguous
    unique = &s;
  }
  if (!unique || head == 0) return std::nullopt;
  used = head;
  return Cursor{unique->type, unique->address, unique->bit, unique->readOnly};
}

bool parseIndex(std::string_view& rest, int64_t& out) {
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  bool negative = false;
  if (!rest.empty() && (rest.front() == '-' || rest.front() == '+')) {
    negative = rest.front() == '-';
    rest.remove_prefix(1);
  }
  if (rest.empty() || !isAsciiDigit(rest.front())) return false;
  int64_t v = 0;
  while (!rest.empty() && isAsciiDigit(rest.front())) {
    if (v > 100'000'000'000'000'000) return false;
    v = v * 10 + (rest.front() - '0');
    rest.remove_prefix(1);
  }
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  out = negative ? -v : v;
  return true;
}

// "[i, j]" (possibly as several bracket groups "[i][j]") on an array.
bool applyIndices(const Module& m, Cursor& cur, std::string_view& rest) {
  const TypeDesc& t = m.types[cur.type];
  if (t.kind != TypeKind::Array || t.element >= m.types.size() || t.dims.empty()) return false;
  uint64_t stride = m.types[t.element].size;
  std::vector<uint64_t> strides(t.dims.size());
  for (size_t d = t.dims.size(); d-- > 0;) {
    strides[d] = stride;
    stride *= t.dims[d].count();
  }
  size_t dim = 0;
  while (dim < t.dims.size()) {
    if (rest.empty() || rest.front() != '[') return false;
    rest.remove_prefix(1);
    for (;;) {
      int64_t index = 0;
      if (dim >= t.dims.size() || !parseIndex(rest, index)) return false;
      if (index < t.dims[dim].lo || index > t.dims[dim].hi) return false;
      cur.address += static_cast<uint64_t>(index - t.dims[dim].lo) * strides[dim];
      ++dim;
      if (rest.empty()) return false;
      const char sep = rest.front();
      rest.remove_prefix(1);
      if (sep == ']') break;
      if (sep != ',') return false;
    }
  }
  cur.type = t.element;
  return true;
}

// ".name" on a struct, or ".N" (a bit) on an integer / bit string.
bool applyMember(const Module& m, Cursor& cur, std::string_view& rest) {
  size_t n = 0;
  while (n < rest.size() && isIdentChar(rest[n])) ++n;
  const std::string_view name = rest.substr(0, n);
  if (name.empty()) return false;
  rest.remove_prefix(n);
  const TypeDesc& t = m.types[cur.type];
  if (t.kind == TypeKind::Struct) {
    for (const Field& f : t.fields) {
      if (!iequalsAscii(f.name, name)) continue;
      cur.type = f.type;
      cur.address = f.absolute ? f.offset : cur.address + f.offset;
      if (f.bit >= 0) {
        cur.address += static_cast<uint64_t>(f.bit) / 8;
        cur.bit = f.bit % 8;
      }
      cur.readOnly = cur.readOnly || f.readOnly;
      return true;
    }
    return false;
  }
  if (t.kind != TypeKind::Elementary || !isInteger(t.elem)) return false;
  if (!std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; })) return false;
  if (name.size() > 2) return false;
  const unsigned bit = static_cast<unsigned>(std::stoi(std::string(name)));
  if (bit >= bitWidth(t.elem)) return false;
  cur.address += bit / 8;
  cur.bit = static_cast<int>(bit % 8);
  for (TypeId i = 0; i < m.types.size(); ++i) {
    if (m.types[i].kind == TypeKind::Elementary && m.types[i].elem == ElemType::Bool) {
      cur.type = i;
      return true;
    }
  }
  return true;  // no BOOL in the table: keep the integer type; bit >= 0 says "one bit"
}

}  // namespace

std::optional<VarRef> resolveVariable(const Module& m, std::string_view path) {
  while (!path.empty() && path.front() == ' ') path.remove_prefix(1);
  while (!path.empty() && path.back() == ' ') path.remove_suffix(1);
  size_t used = 0;
  std::optional<Cursor> cur = findRoot(m, path, used);
  if (!cur) return std::nullopt;
  std::string_view rest = path.substr(used);
  while (!rest.empty()) {
    if (cur->type >= m.types.size() || cur->bit >= 0) return std::nullopt;
    const char c = rest.front();
    if (c == '[') {
      if (!applyIndices(m, *cur, rest)) return std::nullopt;
    } else if (c == '.') {
      rest.remove_prefix(1);
      if (!applyMember(m, *cur, rest)) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  if (cur->address > 0xffffffffu) return std::nullopt;
  return VarRef{cur->type, static_cast<uint32_t>(cur->address), static_cast<int8_t>(cur->bit), cur->readOnly};
}

}  // namespace virtcom::bc
