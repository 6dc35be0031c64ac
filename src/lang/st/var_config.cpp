#include "lang/st/var_config.hpp"

#include <map>

#include "core/ascii.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

struct ProgramDecl {
  Pou* pou = nullptr;
  std::string instance;
};

// The declaration named `name` in the program's VAR blocks, or null.
VarDecl* findDecl(Pou& pou, std::string_view name) {
  for (VarBlock& block : pou.varBlocks)
    for (VarDecl& decl : block.vars)
      for (const DeclName& n : decl.names)
        if (iequalsAscii(n.name, name)) return &decl;
  return nullptr;
}

// The type as written, enough to tell INT from BOOL or WORD (VAR_CONFIG repeats the type).
std::string typeText(const TypeSpec& t) {
  switch (t.kind) {
    case TypeSpecKind::Named: return asciiUpper(t.name);
    case TypeSpecKind::String: return t.wide ? "WSTRING" : "STRING";
    default: return "?";
  }
}

class Applier {
 public:
  Applier(std::vector<CompilationUnit>& units, Diagnostics& diags) : units_(units), diags_(diags) {
    for (CompilationUnit& unit : units)
      for (auto& pou : unit.pous)
        if (pou->kind == PouKind::Program) programs_[asciiUpper(pou->name)] = pou.get();
  }

  void run() {
    for (CompilationUnit& unit : units_)
      for (Configuration& cfg : unit.configurations)
        for (ConfigVar& entry : cfg.configVars) apply(cfg, entry);
  }

 private:
  // `inst.var` or `resource.inst.var` to the program instance's POU.
  Pou* programOf(const Configuration& cfg, const ConfigVar& entry, std::string& instance) {
    const size_t parts = entry.path.size();
    for (const Resource& res : cfg.resources) {
      if (parts == 3 && !iequalsAscii(res.name, entry.path[0])) continue;
      for (const ProgramConfig& p : res.programs) {
        if (!iequalsAscii(p.instanceName, entry.path[parts - 2])) continue;
        instance = p.instanceName;
        auto it = programs_.find(asciiUpper(p.typeName.empty() ? p.instanceName : p.typeName));
        return it == programs_.end() ? nullptr : it->second;
      }
    }
    return nullptr;
  }

  void apply(const Configuration& cfg, ConfigVar& entry) {
    const std::string path = joined(entry.path);
    if (entry.path.size() < 2 || entry.path.size() > 3) {
      diags_.error(diag::E109, entry.loc, "VAR_CONFIG names a variable of a program instance, as inst.var or "
                                          "resource.inst.var; '" + path + "' is neither (members of FB instances "
                                          "cannot be configured)");
      return;
    }
    std::string instance;
    Pou* pou = programOf(cfg, entry, instance);
    if (!pou) {
      diags_.error(diag::E201, entry.loc, "VAR_CONFIG '" + path + "': no program instance '" +
                                              entry.path[entry.path.size() - 2] + "' in configuration " + cfg.name);
      return;
    }
    const std::string& name = entry.path.back();
    VarDecl* decl = findDecl(*pou, name);
    if (!decl) {
      diags_.error(diag::E201, entry.loc, "VAR_CONFIG '" + path + "': program " + pou->name + " declares no '" + name + "'");
      return;
    }
    check(*decl, entry, path, *pou, instance);
  }

  void check(VarDecl& decl, ConfigVar& entry, const std::string& path, Pou& pou, const std::string& instance) {
    const std::string& placeholder = decl.location;
    auto& done = completed_[&decl];
    if (!done.address.empty()) {
      // Located variables live in the PROGRAM type's memory here, not per instance.
      if (!iequalsAscii(done.address, entry.location) || !iequalsAscii(done.instance, instance))
        diags_.error(diag::E109, entry.loc, "VAR_CONFIG '" + path + "': " + pou.name + "." + entry.path.back() +
                                                " was already completed as " + done.address + " for instance " +
                                                done.instance + "; instances of one PROGRAM type share their located "
                                                "variables in virtcom");
      return;
    }
    if (placeholder.size() < 3 || placeholder.back() != '*') {
      diags_.error(diag::E109, entry.loc, "VAR_CONFIG '" + path + "': the variable is declared " +
                                              (placeholder.empty() ? std::string("without AT")
                                                                   : "AT " + placeholder) +
                                              "; VAR_CONFIG completes only an address written with '*' (AT %I*, %Q*, %M*)");
      return;
    }
    // %I* accepts %IX1.0 / %IW2; %IW* only %IW...: the letters before '*' must start the address.
    const std::string_view given = std::string_view(placeholder).substr(0, placeholder.size() - 1);
    // After these two mistakes the declaration keeps its '*' and would be reported again as
    // never completed: the entry's message is the one to read.
    bool consequential = false;
    if (!istartsWithAscii(entry.location, given)) {
      diags_.error(diag::E109, entry.loc, "VAR_CONFIG '" + path + "': " + entry.location + " does not complete " +
                                              placeholder + " (the area and size must be those of the declaration)");
      consequential = true;
    } else if (typeText(entry.type) != typeText(decl.type)) {
      diags_.error(diag::E109, entry.loc, "VAR_CONFIG '" + path + "' is declared " + typeText(entry.type) +
                                              " here and " + typeText(decl.type) + " in program " + pou.name);
      consequential = true;
    }
    if (consequential) {
      decl.location.clear();
      return;
    }
    if (decl.names.size() > 1) {
      diags_.error(diag::E109, entry.loc, "VAR_CONFIG '" + path + "': declare '" + entry.path.back() +
                                              "' alone (a, b AT %I* : ... would put both at one address)");
      return;
    }
    decl.location = entry.location;
    if (entry.init) decl.init = std::move(entry.init);
    done = {entry.location, instance};
  }

  static std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : ".") + p;
    return out;
  }

  struct Completion {
    std::string address;
    std::string instance;
  };

  std::vector<CompilationUnit>& units_;
  Diagnostics& diags_;
  std::map<std::string, Pou*> programs_;
  std::map<const VarDecl*, Completion> completed_;
};

}  // namespace

void applyVarConfig(std::vector<CompilationUnit>& units, Diagnostics& diags) { Applier(units, diags).run(); }

}  // namespace virtcom::st
