#include "lang/st/codegen/init_program.hpp"

#include "lang/syntax/ast_clone.hpp"

#include <algorithm>
#include <map>

namespace virtcom::st {

namespace {

CallArg cloneArg(const CallArg& a) { return CallArg{a.name, a.output, a.negated, cloneExprOrNull(a.value), a.loc}; }

ExprPtr makeExpr(ExprKind kind, SourceLocation loc, std::string text = {}) {
  auto e = std::make_unique<Expr>();
  e->kind = kind;
  e->loc = loc;
  e->text = std::move(text);
  return e;
}

ExprPtr member(ExprPtr object, const std::string& name) {
  ExprPtr e = makeExpr(ExprKind::Member, object->loc, name);
  e->lhs = std::move(object);
  return e;
}

ExprPtr intLiteral(int64_t v, SourceLocation loc) {
  ExprPtr lit = makeExpr(ExprKind::IntLit, loc);
  lit->intValue = static_cast<uint64_t>(v < 0 ? -v : v);
  if (v >= 0) return lit;
  ExprPtr neg = makeExpr(ExprKind::Unary, loc);
  neg->unaryOp = UnaryOp::Neg;
  neg->lhs = std::move(lit);
  return neg;
}

// Where an instance is declared: its declaration arguments may name the container's other
// variables (`state : INT; sm : FB_Sm(state);`), which the init program reaches as
// `<container path>.state`. Globals have no container.
struct Container {
  const Expr* path = nullptr;
  const PouSym* pou = nullptr;
};

// Which of the CODESYS lifecycle methods the calls are for.
enum class Lifecycle { Init, Exit };

class InitCalls {
 public:
  InitCalls(const ProgramModel& model, const TypeTable& types, StmtList& out, Lifecycle kind = Lifecycle::Init)
      : model_(model), types_(types), out_(out), method_(kind == Lifecycle::Init ? "FB_INIT" : "FB_EXIT") {}

  // Emits the FB_init (FB_exit) calls for the variable at `path` of `type` and everything
  // inside it, nested instances first.
  void visit(const Expr& path, TypeId type, const std::vector<CallArg>* args, SourceLocation loc,
             Container container = {}) {
    if (!needsInit(type)) return;  // also keeps arrays of plain values from being walked
    const bc::TypeDesc& d = types_[type];
    if (d.kind == bc::TypeKind::Array) {
      std::vector<int64_t> index;
      for (const auto& dim : d.dims) index.push_back(dim.lo);
      while (true) {
        ExprPtr element = makeExpr(ExprKind::Index, loc);
        element->lhs = cloneExpr(path);
        for (int64_t i : index) element->items.push_back(intLiteral(i, loc));
        visit(*element, d.element, nullptr, loc);
        size_t k = index.size();
        while (k > 0 && index[k - 1] == d.dims[k - 1].hi) {
          index[k - 1] = d.dims[k - 1].lo;
          --k;
        }
        if (k == 0) return;
        ++index[k - 1];
      }
    }
    auto fb = model_.fbByType.find(type);
    if (fb == model_.fbByType.end()) {
      for (const auto& f : d.fields) visit(*member(cloneExpr(path), f.name), f.type, nullptr, loc);
      return;
    }
    for (const auto& m : fb->second->members)
      if (m.storage == Storage::Instance && !m.byReference && m.name.find('.') == std::string::npos)
        visit(*member(cloneExpr(path), m.name), m.type, m.decl ? &m.decl->fbInitArgs : nullptr, m.loc,
              Container{&path, fb->second});
    auto method = fb->second->methods.find(method_);
    if (method != fb->second->methods.end()) call(path, *method->second, args, loc, container);
  }

 private:
  bool needsInit(TypeId type) {
    if (type == kNoType) return false;
    if (auto it = needs_.find(type); it != needs_.end()) return it->second;
    needs_[type] = false;  // a cycle contributes nothing
    const bc::TypeDesc& d = types_[type];
    bool needs = false;
    if (d.kind == bc::TypeKind::Array) {
      needs = needsInit(d.element);
    } else if (auto fb = model_.fbByType.find(type); fb != model_.fbByType.end()) {
      needs = fb->second->methods.count(method_) > 0;
      for (const auto& m : fb->second->members)
        needs = needs || (m.storage == Storage::Instance && !m.byReference && needsInit(m.type));
    } else if (d.kind == bc::TypeKind::Struct) {
      for (const auto& f : d.fields) needs = needs || needsInit(f.type);
    }
    return needs_[type] = needs;
  }

  static void qualifyContainerNames(ExprPtr& e, Container container) {
    if (!container.pou) return;
    if (e->kind == ExprKind::Name && container.pou->memberIndex.count(upper(e->text))) {
      e = member(cloneExpr(*container.path), e->text);
      return;
    }
    if (e->lhs) qualifyContainerNames(e->lhs, container);
    if (e->rhs) qualifyContainerNames(e->rhs, container);
    for (auto& item : e->items)
      if (item) qualifyContainerNames(item, container);
    for (auto& arg : e->args)
      if (arg.value) qualifyContainerNames(arg.value, container);
  }

  void call(const Expr& path, const PouSym& init, const std::vector<CallArg>* args, SourceLocation loc,
            Container container) {
    ExprPtr e = makeExpr(ExprKind::Call, loc);
    e->lhs = member(cloneExpr(path), init.name);
    // Positional declaration arguments (`inst : FB_T('a', 1)`, as TwinCAT libraries write
    // them) follow bInitRetains and bInCopyCode, FB_init's first two inputs; the flags are then
    // passed by position too, so the call is in one form and the ordinary argument binding
    // reports a wrong count.
    // The declaration's arguments are FB_init's; FB_exit takes bInCopyCode alone.
    if (method_ != "FB_INIT") args = nullptr;
    bool positional = args && !args->empty() && args->front().name.empty();
    auto flag = [&](const char* name, bool value) {
      for (const VarInfo* p : init.params)
        if (upper(p->name) == name) {
          ExprPtr v = makeExpr(ExprKind::BoolLit, loc);
          v->intValue = value;
          e->args.push_back(CallArg{positional ? std::string() : p->name, false, false, std::move(v), loc});
        }
    };
    if (method_ == "FB_INIT") flag("BINITRETAINS", true);
    flag("BINCOPYCODE", false);
    if (args)
      for (const auto& a : *args) {
        e->args.push_back(cloneArg(a));
        if (e->args.back().value) qualifyContainerNames(e->args.back().value, container);
      }
    auto stmt = std::make_unique<Stmt>();
    stmt->kind = StmtKind::Call;
    stmt->loc = loc;
    stmt->expr = std::move(e);
    out_.push_back(std::move(stmt));
  }

  const ProgramModel& model_;
  const TypeTable& types_;
  StmtList& out_;
  const std::string method_;
  std::map<TypeId, bool> needs_;
};

}  // namespace

namespace {

std::unique_ptr<Pou> buildLifecycleProgram(const ProgramModel& model, const TypeTable& types, Lifecycle kind) {
  auto pou = std::make_unique<Pou>();
  pou->kind = PouKind::Program;
  pou->name = kind == Lifecycle::Init ? "__INIT" : "__EXIT";
  pou->hasBody = true;
  InitCalls calls(model, types, pou->body, kind);
  for (const auto& g : model.globals)
    calls.visit(*makeExpr(ExprKind::Name, g.var.loc, g.var.name), g.var.type, g.var.decl ? &g.var.decl->fbInitArgs : nullptr, g.var.loc);
  for (const auto& inst : model.programInstances)
    calls.visit(*makeExpr(ExprKind::Name, inst.pou->ast->loc, inst.name), inst.pou->instanceType, nullptr, inst.pou->ast->loc);
  if (pou->body.empty()) return nullptr;
  // FB_exit undoes in the reverse order: program instances before globals, a container
  // before the instances inside it.
  if (kind == Lifecycle::Exit) std::reverse(pou->body.begin(), pou->body.end());
  return pou;
}

}  // namespace

std::unique_ptr<Pou> buildInitProgram(const ProgramModel& model, const TypeTable& types) {
  return buildLifecycleProgram(model, types, Lifecycle::Init);
}

std::unique_ptr<Pou> buildExitProgram(const ProgramModel& model, const TypeTable& types) {
  return buildLifecycleProgram(model, types, Lifecycle::Exit);
}

namespace {

StmtList buildFrameLifecycleCalls(const ProgramModel& model, const TypeTable& types, const PouSym& pou, Lifecycle kind) {
  StmtList body;
  InitCalls calls(model, types, body, kind);
  for (const VarInfo& v : pou.locals)
    if ((v.section == VarSection::Var || v.section == VarSection::Temp) && !v.byReference)
      calls.visit(*makeExpr(ExprKind::Name, v.loc, v.name), v.type, v.decl ? &v.decl->fbInitArgs : nullptr, v.loc);
  if (kind == Lifecycle::Exit) std::reverse(body.begin(), body.end());
  return body;
}

}  // namespace

StmtList buildFrameInitCalls(const ProgramModel& model, const TypeTable& types, const PouSym& pou) {
  return buildFrameLifecycleCalls(model, types, pou, Lifecycle::Init);
}

StmtList buildFrameExitCalls(const ProgramModel& model, const TypeTable& types, const PouSym& pou) {
  return buildFrameLifecycleCalls(model, types, pou, Lifecycle::Exit);
}

}  // namespace virtcom::st
