// Relations between FB and interface types (EXTENDS, IMPLEMENTS), for the checks and for
// dynamic dispatch.
#include "lang/st/codegen/check.hpp"

namespace virtcom::st {

namespace {

// The depth limit guards against EXTENDS cycles, which the declarer reports but keeps.
bool extendsWithin(const ProgramModel& m, const std::string& itf, const std::string& target, int depth) {
  if (itf == target) return true;
  if (depth > 16) return false;
  auto it = m.interfaces.find(itf);
  if (it == m.interfaces.end()) return false;
  for (const auto& b : it->second.bases)
    if (extendsWithin(m, b, target, depth + 1)) return true;
  return false;
}

}  // namespace

bool derivesFrom(const PouSym* c, const PouSym* base) {
  for (; c; c = c->base)
    if (c == base) return true;
  return false;
}

bool sameOrDerivedFb(const ProgramModel& m, TypeId actual, TypeId wanted) {
  if (actual == wanted) return true;
  auto a = m.fbByType.find(actual), w = m.fbByType.find(wanted);
  return a != m.fbByType.end() && w != m.fbByType.end() && derivesFrom(a->second, w->second);
}

bool interfaceExtends(const ProgramModel& m, const std::string& itf, const std::string& target) {
  return extendsWithin(m, itf, target, 0);
}

bool implementsInterface(const ProgramModel& m, const PouSym* c, const std::string& itf) {
  for (; c; c = c->base)
    for (const auto& i : c->interfaces)
      if (interfaceExtends(m, i, itf)) return true;
  return false;
}

}  // namespace virtcom::st
