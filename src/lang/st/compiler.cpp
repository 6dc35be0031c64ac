#include "lang/st/compiler.hpp"

#include <filesystem>
#include <functional>

#include "bytecode/verifier.hpp"
#include "lang/st/codegen/codegen.hpp"
#include "lang/st/compile_cache.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/codegen/init_program.hpp"
#include "lang/st/parse/parser.hpp"
#include "lang/st/prelude.hpp"
#include "lang/st/var_config.hpp"

namespace virtcom::st {

namespace {

bc::PouKind moduleKind(PouKind k) {
  switch (k) {
    case PouKind::Program: return bc::PouKind::Program;
    case PouKind::Function: return bc::PouKind::Function;
    case PouKind::FunctionBlock: return bc::PouKind::FunctionBlock;
    case PouKind::Method: return bc::PouKind::Method;
    case PouKind::Action: return bc::PouKind::Action;
    case PouKind::PropertyGet: return bc::PouKind::PropertyGet;
    case PouKind::PropertySet: return bc::PouKind::PropertySet;
  }
  return bc::PouKind::Function;
}

bool hasCode(const PouSym& p) {
  if (p.isInterfaceMethod) return false;
  if (p.kind == PouKind::Method && !p.ast->hasBody) return false;
  return true;
}

// Reports calls that (directly or through other POUs) reach the caller again.
void checkRecursion(ProgramModel& model, Diagnostics& diags) {
  enum Mark { White, Grey, Black };
  std::map<PouSym*, Mark> mark;
  std::function<void(PouSym*)> visit = [&](PouSym* p) {
    mark[p] = Grey;
    for (PouSym* c : p->callees) {
      // CODESYS allows recursive METHODs (bounded by the stack at run time); FUNCTIONs and FBs may not recurse.
      bool mayRecurse = c->kind == PouKind::Method || c->kind == PouKind::PropertyGet || c->kind == PouKind::PropertySet;
      if (mark[c] == Grey && !mayRecurse) {
        diags.error(diag::E207, p->ast->loc, "'" + p->qualifiedName + "' calls '" + c->qualifiedName +
                                                 "' recursively; IEC 61131-3 does not allow recursion");
        continue;
      }
      if (mark[c] == White) visit(c);
    }
    mark[p] = Black;
  };
  for (auto& p : model.pous)
    if (mark[p.get()] == White) visit(p.get());
}

void fillSymbols(ProgramModel& model, bc::Module& module, TypeTable& types) {
  for (const auto& g : model.globals) {
    bc::Symbol s;
    s.name = g.listName.empty() ? g.var.name : g.listName + "." + g.var.name;
    s.type = g.var.type;
    s.address = g.var.offset;
    s.readOnly = g.var.readOnly;
    s.retain = g.var.retain;
    s.bit = static_cast<int8_t>(g.var.bit);
    module.symbols.push_back(s);
  }
  for (const auto& inst : model.programInstances) {
    module.symbols.push_back({inst.name, inst.pou->instanceType, inst.address, false});
    module.programs.push_back({inst.name, inst.pou->bcIndex, inst.address});
  }
  for (const auto& t : model.tasks) {
    bc::TaskInfo info;
    info.name = t.name;
    info.intervalNs = t.intervalNs;
    info.priority = t.priority;
    info.isDefault = t.isDefault;
    for (const auto& name : t.programInstances)
      for (size_t i = 0; i < model.programInstances.size(); ++i)
        if (upper(model.programInstances[i].name) == name) info.programs.push_back(static_cast<uint32_t>(i));
    module.tasks.push_back(std::move(info));
  }
  (void)types;
}

// Gives every configured program instance with arguments its caller PROGRAM (see
// configCallerName); the arguments move into the caller's call, where they are checked like
// the arguments of any call.
void addConfigCallers(std::vector<CompilationUnit>& units) {
  for (auto& unit : units)
    for (auto& cfg : unit.configurations)
      for (auto& res : cfg.resources)
        for (auto& p : res.programs) {
          if (p.args.empty()) continue;
          auto callee = std::make_unique<Expr>();
          callee->kind = ExprKind::Name;
          callee->text = p.instanceName;
          callee->loc = p.loc;
          auto call = std::make_unique<Expr>();
          call->kind = ExprKind::Call;
          call->loc = p.loc;
          call->lhs = std::move(callee);
          call->args = std::move(p.args);
          auto stmt = std::make_unique<Stmt>();
          stmt->kind = StmtKind::Call;
          stmt->loc = p.loc;
          stmt->expr = std::move(call);
          stmt->cover = CoverRole::Generated;  // the CONFIGURATION's call, not a statement written
          auto caller = std::make_unique<Pou>();
          caller->kind = PouKind::Program;
          caller->name = configCallerName(p.instanceName);
          caller->loc = p.loc;
          caller->endLoc = p.loc;
          caller->hasBody = true;
          caller->body.push_back(std::move(stmt));
          unit.pous.push_back(std::move(caller));
        }
}

// The coverage counters (8 bytes each) go into the static image after everything else, and
// every COVER's Bx, the probe's index so far, becomes its counter's address.
void placeCoverageCounters(bc::Module& module, ImageBuilder& image) {
  bc::CoverageTable& table = module.coverage;
  if (table.probes.empty()) return;
  table.counterAddress = image.allocate(table.counterBytes(), 8);
  for (bc::Instr& ins : module.code)
    if (ins.op == bc::Op::COVER) ins = bc::Instr::abx(bc::Op::COVER, 0, table.counterAddress + 8 * ins.bx());
}

}  // namespace

std::vector<CompilationUnit> parseInputs(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                         Diagnostics& diags, NodeId& nextNodeId) {
  std::vector<CompilationUnit> units;
  for (const auto& in : inputs) {
    uint32_t id = sources.addFile(in.path, in.text);
    const FrontEnd& parse = in.frontEnd ? in.frontEnd : FrontEnd(parseFile);
    units.push_back(parse(id, sources.text(id), diags, nextNodeId));
    for (auto& gvl : units.back().globals)
      if (gvl.name.empty()) gvl.name = std::filesystem::path(in.path).stem().string();
  }
  return units;
}

namespace {

std::unique_ptr<bc::Module> compileFresh(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                         Diagnostics& diags, const CompileOptions& options) {
  auto module = std::make_unique<bc::Module>();
  std::vector<CompilationUnit> units;
  NodeId nextId = 0;
  uint32_t libraryFile = sources.addFile(std::string(kStandardLibraryPath), std::string(standardLibrarySource()));
  units.push_back(parseFile(libraryFile, sources.text(libraryFile), diags, nextId));
  size_t libraryPous = units.front().pous.size();
  for (CompilationUnit& unit : parseInputs(inputs, sources, diags, nextId)) units.push_back(std::move(unit));
  addConfigCallers(units);
  module->files.clear();
  for (uint32_t i = 0; i < sources.fileCount(); ++i) module->files.push_back(sources.path(i));
  if (diags.hasErrors()) {
    diags.sortByLocation();
    return nullptr;
  }
  applyVarConfig(units, diags);  // its mistakes do not hide those of the declarations
  ProgramModel model;
  TypeTable types(module->types);
  ImageBuilder image(module->initialImage);
  Declarer declarer(units, diags, types, model, image, *module);
  declarer.run();
  module->writableEnd = image.size();  // variables are all placed; constant data follows
  for (auto& p : model.pous)
    for (size_t i = 0; i < libraryPous; ++i)
      if (p->ast == units.front().pous[i].get() || (p->owner && p->owner->ast == units.front().pous[i].get())) p->isLibrary = true;
  bool noProgram = model.programInstances.empty();
  if (noProgram && !options.library && !diags.hasErrors())
    diags.error(diag::E217, {kNoFile, 0, 0}, "no PROGRAM to run: declare a PROGRAM (e.g. PROGRAM MAIN ... END_PROGRAM)");
  if (diags.hasErrors()) {
    diags.sortByLocation();
    return nullptr;
  }
  std::unique_ptr<Pou> initAst = buildInitProgram(model, types), exitAst = buildExitProgram(model, types);
  auto addLifecyclePou = [&](const std::unique_ptr<Pou>& ast) -> PouSym* {
    if (!ast) return nullptr;
    auto sym = std::make_unique<PouSym>();
    sym->name = sym->qualifiedName = ast->name;
    sym->ast = ast.get();
    model.pous.push_back(std::move(sym));
    return model.pous.back().get();
  };
  PouSym* initPou = addLifecyclePou(initAst);
  PouSym* exitPou = addLifecyclePou(exitAst);
  // Every POU with code gets its slot first, so calls can name any callee.
  for (auto& p : model.pous) {
    if (!hasCode(*p)) continue;
    p->bcIndex = static_cast<uint32_t>(module->pous.size());
    bc::PouInfo info;
    info.name = p->qualifiedName;
    info.kind = p.get() == initPou || p.get() == exitPou ? bc::PouKind::Init : moduleKind(p->kind);
    info.instanceType = p->kind == PouKind::FunctionBlock || p->kind == PouKind::Program ? p->instanceType : bc::kNoType;
    module->pous.push_back(info);
  }
  if (initPou) module->initPou = initPou->bcIndex;
  if (exitPou) module->exitPou = exitPou->bcIndex;
  CompileContext ctx{model, types, declarer, *module, image, diags, options.coverage};
  for (auto& p : model.pous) {
    if (!hasCode(*p)) continue;
    PouCompiler pc(ctx, *p);
    pc.compile();
  }
  checkRecursion(model, diags);
  if (diags.hasErrors()) {
    diags.sortByLocation();
    return nullptr;
  }
  declarer.buildTemplates();
  placeCoverageCounters(*module, image);
  for (auto& p : model.pous) {
    if (!hasCode(*p)) continue;
    module->pous[p->bcIndex].frameSize = p->frameSize;
    module->pous[p->bcIndex].frameTemplate = p->frameTemplate;
  }
  fillSymbols(model, *module, types);
  module->staticSize = image.size();
  std::stable_sort(module->lines.begin(), module->lines.end(),
                   [](const bc::LineEntry& a, const bc::LineEntry& b) { return a.pc < b.pc; });
  diags.sortByLocation();
  std::string problem = bc::verifyModule(*module);
  if (!problem.empty()) {
    diags.error("E999", {kNoFile, 0, 0}, "internal compiler error: generated code failed verification: " + problem);
    return nullptr;
  }
  return module;
}

}  // namespace

std::unique_ptr<bc::Module> compileProgram(const std::vector<SourceInput>& inputs, SourceManager& sources,
                                           Diagnostics& diags, CompileOptions options) {
  const std::string key = options.cacheDir.empty() ? std::string() : moduleCacheKey(inputs, sources, options);
  if (!key.empty())
    if (auto cached = loadCachedModule(options.cacheDir, key, inputs, sources)) return cached;
  const size_t diagnosticsBefore = diags.all().size();
  auto module = compileFresh(inputs, sources, diags, options);
  if (module && !key.empty() && diags.all().size() == diagnosticsBefore) storeCachedModule(options.cacheDir, key, *module);
  return module;
}

}  // namespace virtcom::st
