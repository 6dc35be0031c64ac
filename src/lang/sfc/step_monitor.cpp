#include "lang/sfc/step_monitor.hpp"

#include "lang/sfc/lower.hpp"

namespace virtcom::sfc {

namespace {

void collect(const bc::Module& m, bc::TypeId type, const std::string& path, std::vector<StepVariable>& out) {
  const bc::TypeDesc& t = m.types[type];
  for (const bc::Field& f : t.fields) {
    if (f.hidden || f.absolute || f.type >= m.types.size()) continue;
    const bc::TypeDesc& ft = m.types[f.type];
    if (ft.kind != bc::TypeKind::Struct) continue;
    std::string fieldPath = path + "." + f.name;
    if (ft.name != kStepTypeName) {
      collect(m, f.type, fieldPath, out);
      continue;
    }
    auto x = bc::resolveVariable(m, fieldPath + ".X");
    auto t = bc::resolveVariable(m, fieldPath + ".T");
    if (x && t) out.push_back({fieldPath, x->address, t->address});
  }
}

}  // namespace

std::vector<StepVariable> findSteps(const bc::Module& module) {
  std::vector<StepVariable> steps;
  for (const bc::Symbol& s : module.symbols) {
    bool isProgram = false;
    for (const bc::ProgramInstance& p : module.programs) isProgram = isProgram || p.name == s.name;
    if (isProgram && s.type < module.types.size()) collect(module, s.type, s.name, steps);
  }
  return steps;
}

void formatActiveSteps(const std::vector<StepVariable>& steps, const uint8_t* memory, std::string& out) {
  out.clear();
  for (const StepVariable& s : steps) {
    if (memory[s.activeAddress] == 0) continue;
    if (!out.empty()) out += ' ';
    out += s.path;
  }
}

}  // namespace virtcom::sfc
