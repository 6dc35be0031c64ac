// Lowering of rule tables to ST (lower.hpp).
#include "lang/ad/lower.hpp"

#include <memory>

#include "lang/ad/decompose.hpp"
#include "lang/ad/ladder.hpp"
#include "lang/ad/reader.hpp"
#include "lang/syntax/ast_builder.hpp"

namespace virtcom::ad {

namespace {

// Where a rule is in the file (its line in the coverage files): the arc of its unit into its
// first output, so each rule of a unit split into several has its own line.
SourceLocation ruleLocation(const Diagram& d, const LogicUnit& unit, const Rule& rule) {
  for (size_t a : unit.arcs)
    if (!rule.actions.empty() && d.arcs[a].to == rule.actions.front().node) return d.arcs[a].loc;
  return unit.arcs.empty() ? d.loc : d.arcs[unit.arcs.front()].loc;
}

class Lowering {
 public:
  Lowering(const Program& program, st::NodeId& nextNodeId) : program_(program), b_(nextNodeId) {}

  std::unique_ptr<st::Pou> run() {
    auto pou = std::make_unique<st::Pou>();
    pou->kind = st::PouKind::Program;
    pou->name = program_.name;
    pou->loc = pou->endLoc = program_.loc;
    pou->hasBody = true;
    for (const Port& port : program_.ports) declarePort(port);
    for (const Diagram& d : program_.diagrams) {
      pou->actions.push_back(lowerDiagram(d));
      b_.at(d.loc);
      pou->body.push_back(b_.callStmt(d.name));
    }
    b_.at(program_.loc);
    pou->varBlocks.push_back(b_.varBlock(st::VarSection::Var, std::move(vars_)));
    if (rulesLowered_ > 0) {
      std::vector<st::VarDecl> hidden;
      hidden.push_back(b_.arrayDecl(kFiredVariable, "BOOL", rulesLowered_, true));
      pou->varBlocks.push_back(b_.varBlock(st::VarSection::Var, std::move(hidden)));
    }
    return pou;
  }

 private:
  void declarePort(const Port& port) {
    b_.at(port.loc);
    st::VarDecl decl = b_.varDecl(port.name, "BOOL", false);
    decl.location = port.address;
    vars_.push_back(std::move(decl));
  }

  std::unique_ptr<st::Pou> lowerDiagram(const Diagram& d) {
    DiagramTables tables = decompose(d);
    auto action = std::make_unique<st::Pou>();
    action->kind = st::PouKind::Action;
    action->name = d.name;
    action->loc = action->endLoc = d.loc;
    action->hasBody = true;
    for (const Node& n : d.nodes) declareNode(d, n, tables);
    b_.generated(true);  // the rules count as rules (RuleFired), not by the lines of their parts
    for (const Rule& rule : tables.rules) lowerRule(d, tables.units[rule.unit], rule, action->body);
    b_.generated(false);
    action->ladder = ladderOf(d, tables);
    return action;
  }

  void declareNode(const Diagram& d, const Node& n, const DiagramTables& tables) {
    b_.at(n.loc);
    if (isBlock(n.kind)) vars_.push_back(b_.varDecl(n.id, blockTypeOf(n), false));
    if (!isJoin(n.kind)) return;
    for (const Rule& rule : tables.rules)
      for (const GroupDefinition& g : rule.groups)
        if (&d.nodes[g.bar] == &n) return vars_.push_back(b_.varDecl(n.id, "BOOL", false));
  }

  st::ExprPtr activityState(const Node& n) {
    if (isBlock(n.kind)) return b_.member(n.id, blockOutputOf(n));
    if (!n.variable.empty() && n.variable[0] == '%') {
      st::ExprPtr e = b_.name(n.variable);
      e->kind = st::ExprKind::DirectAddr;
      return e;
    }
    return dottedName(n.variable);
  }

  // GVL.x -> Member(Name GVL, x); a plain name -> Name.
  st::ExprPtr dottedName(std::string_view path) {
    size_t dot = path.rfind('.');
    if (dot == std::string_view::npos) return b_.name(path);
    st::ExprPtr e = b_.member("", path.substr(dot + 1));
    e->lhs = dottedName(path.substr(0, dot));
    return e;
  }

  st::ExprPtr condition(const Diagram& d, const Condition& c) {
    const Node& n = d.nodes[c.node];
    b_.at(n.loc);
    switch (c.kind) {
      case Condition::Kind::Term: return c.on ? activityState(n) : b_.notOf(activityState(n));
      case Condition::Kind::Group: return b_.name(n.id);
      default: break;
    }
    st::BinaryOp op = c.kind == Condition::Kind::And ? st::BinaryOp::And : st::BinaryOp::Or;
    st::ExprPtr out;
    for (const Condition& operand : c.operands) {
      st::ExprPtr e = condition(d, operand);
      out = out ? b_.binary(op, std::move(out), std::move(e)) : std::move(e);
    }
    return out;
  }

  // The rule's IF goes into its fired flag first (evaluated once, before the rule's own writes,
  // and readable by --trace-rules); the writes and the blocks' inputs then read the flag. The
  // writes' `IF __ad_fired[k]` is there for every rule (empty for one that only drives blocks):
  // entering it is the rule's firing to code coverage (st::CoverRole::RuleFired).
  void lowerRule(const Diagram& d, const LogicUnit& unit, const Rule& rule, st::StmtList& body) {
    for (const GroupDefinition& g : rule.groups) {
      st::ExprPtr value = condition(d, g.value);
      b_.at(d.nodes[g.bar].loc);
      body.push_back(b_.assign(b_.name(d.nodes[g.bar].id), std::move(value)));
    }
    uint64_t flag = ++rulesLowered_;
    st::ExprPtr cond = condition(d, rule.condition);
    body.push_back(b_.assign(b_.index(kFiredVariable, flag), std::move(cond)));
    st::StmtList writes;
    for (const RuleAction& a : rule.actions) {
      const Node& target = d.nodes[a.node];
      b_.at(target.loc);
      if (isBlock(target.kind)) continue;
      writes.push_back(b_.assign(activityState(target), b_.boolLit(a.on)));
    }
    st::StmtPtr fired = b_.ifThen(b_.index(kFiredVariable, flag), std::move(writes));
    fired->cover = st::CoverRole::RuleFired;
    fired->coverName = rule.index;
    fired->coverLoc = ruleLocation(d, unit, rule);
    body.push_back(std::move(fired));
    for (const RuleAction& a : rule.actions)
      if (isBlock(d.nodes[a.node].kind)) body.push_back(driveBlock(d.nodes[a.node], a.on, flag));
  }

  // A counter's reset is assigned (the block runs at its counting rule); the driven input
  // calls the block with its preset.
  st::StmtPtr driveBlock(const Node& block, bool on, uint64_t flag) {
    b_.at(block.loc);
    std::string_view input = blockInputOf(block, on);
    if (!on) return b_.assign(b_.member(block.id, input), b_.index(kFiredVariable, flag));
    std::vector<std::pair<std::string, st::ExprPtr>> args;
    args.emplace_back(std::string(input), b_.index(kFiredVariable, flag));
    if (block.kind == NodeKind::Timer) args.emplace_back("PT", b_.timeLit(block.presetNs));
    if (block.kind == NodeKind::Counter) args.emplace_back("PV", b_.intLit(block.presetCount));
    return b_.callNamed(block.id, std::move(args));
  }

  const Program& program_;
  st::AstBuilder b_;
  std::vector<st::VarDecl> vars_;
  uint64_t rulesLowered_ = 0;  // rules of the diagrams lowered so far: the last fired flag used
};

}  // namespace

st::CompilationUnit lowerProgram(const Program& program, uint32_t fileId, st::NodeId& nextNodeId) {
  st::CompilationUnit unit;
  unit.fileId = fileId;
  unit.pous.push_back(Lowering(program, nextNodeId).run());
  return unit;
}

namespace {

// Lowers what `read` made of the file, or gives an empty unit if it reported an error.
template <class Read>
st::CompilationUnit importWith(Read read, uint32_t fileId, std::string_view text, Diagnostics& diags,
                               st::NodeId& nextNodeId) {
  size_t errorsBefore = diags.errorCount();
  Program program = read(fileId, text, diags);
  if (diags.errorCount() != errorsBefore) {
    st::CompilationUnit empty;
    empty.fileId = fileId;
    return empty;
  }
  return lowerProgram(program, fileId, nextNodeId);
}

}  // namespace

st::CompilationUnit importDiagrams(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId) {
  return importWith(readProgram, fileId, text, diags, nextNodeId);
}

st::CompilationUnit importXmlDiagrams(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId) {
  return importWith(readXmlProgram, fileId, text, diags, nextNodeId);
}

}  // namespace virtcom::ad
