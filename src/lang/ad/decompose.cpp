// Logic units, their types and their rules (decompose.hpp).
#include "lang/ad/decompose.hpp"

#include <algorithm>
#include <cassert>
#include <map>

namespace virtcom::ad {

namespace {

struct LuTypeInfo {
  std::string_view label, description;
};
constexpr LuTypeInfo kLuTypes[] = {
#define X(type, label, description) {label, description},
#include "lang/ad/lu_types.def"
#undef X
};

void addOnce(std::vector<size_t>& list, size_t value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

class Decomposer {
 public:
  explicit Decomposer(const Diagram& d) : d_(d), barUnit_(d.nodes.size(), SIZE_MAX) {}

  DiagramTables run() {
    DiagramTables tables;
    tables.diagram = &d_;
    for (size_t a = 0; a < d_.arcs.size(); ++a) assignArc(a, tables.units);
    for (size_t u = 0; u < tables.units.size(); ++u) {
      LogicUnit& unit = tables.units[u];
      orderBars(unit);
      unit.type = classify(unit);
      addRules(u, unit, tables.rules);
    }
    return tables;
  }

 private:
  const Node& node(size_t n) const { return d_.nodes[n]; }
  bool barAt(size_t n) const { return isBar(node(n).kind); }

  // An arc between two activities is a unit of its own; arcs touching bars join the unit of
  // every bar connected to them through other bars.
  void assignArc(size_t a, std::vector<LogicUnit>& units) {
    const Arc& arc = d_.arcs[a];
    if (isTerminal(node(arc.from).kind) || isTerminal(node(arc.to).kind)) return;
    size_t bar = barAt(arc.from) ? arc.from : barAt(arc.to) ? arc.to : SIZE_MAX;
    size_t u = bar == SIZE_MAX ? SIZE_MAX : barUnit_[bar];
    if (u == SIZE_MAX) {
      u = units.size();
      units.emplace_back();
      if (bar != SIZE_MAX) markBarComponent(bar, u);
    }
    LogicUnit& unit = units[u];
    unit.arcs.push_back(a);
    if (!barAt(arc.from)) addOnce(unit.inputs, arc.from);
    if (!barAt(arc.to)) addOnce(unit.outputs, arc.to);
  }

  void markBarComponent(size_t bar, size_t u) {
    std::vector<size_t> todo{bar};
    barUnit_[bar] = u;
    while (!todo.empty()) {
      size_t b = todo.back();
      todo.pop_back();
      for (const Arc& arc : d_.arcs) {
        size_t other = arc.from == b ? arc.to : arc.to == b ? arc.from : SIZE_MAX;
        if (other == SIZE_MAX || !barAt(other) || barUnit_[other] != SIZE_MAX) continue;
        barUnit_[other] = u;
        todo.push_back(other);
      }
    }
  }

  // Bars in flow order: repeatedly the first bar no remaining bar feeds.
  void orderBars(LogicUnit& unit) {
    std::vector<size_t> bars;
    for (size_t a : unit.arcs)
      for (size_t n : {d_.arcs[a].from, d_.arcs[a].to})
        if (barAt(n)) addOnce(bars, n);
    while (!bars.empty()) {
      auto unfed = std::find_if(bars.begin(), bars.end(), [&](size_t bar) {
        return std::none_of(unit.arcs.begin(), unit.arcs.end(), [&](size_t a) {
          return d_.arcs[a].to == bar && std::count(bars.begin(), bars.end(), d_.arcs[a].from) > 0;
        });
      });
      // checkProgram reports every cycle among bars (A010), so one is always unfed.
      assert(unfed != bars.end());
      if (unfed == bars.end()) return;
      unit.bars.push_back(*unfed);
      bars.erase(unfed);
    }
  }

  bool feedsBar(size_t bar) const {
    for (const Arc& arc : d_.arcs)
      if (arc.from == bar && barAt(arc.to)) return true;
    return false;
  }

  LuType classify(const LogicUnit& unit) const {
    if (unit.bars.empty()) {
      bool block = isBlock(node(unit.inputs.front()).kind) || isBlock(node(unit.outputs.front()).kind);
      return block ? LuType::FunctionBlock : LuType::Basic;
    }
    if (unit.bars.size() == 1) return LuType::LogicFlow;
    for (size_t b : unit.bars)
      if (node(b).kind == NodeKind::AndSplit && feedsBar(b)) return LuType::SplitPrecedent;
    return LuType::JoinPrecedent;
  }

  // A join that feeds another bar is grouped: the rule names it instead of repeating it.
  Condition arcTerm(const Arc& arc) const {
    if (!barAt(arc.from)) return {Condition::Kind::Term, arc.from, arc.kind != ArcKind::NotIn, {}};
    if (isJoin(node(arc.from).kind) && barAt(arc.to)) return {Condition::Kind::Group, arc.from, true, {}};
    return barValue(arc.from);
  }

  Condition barValue(size_t bar) const {
    Condition::Kind kind = node(bar).kind == NodeKind::OrJoin ? Condition::Kind::Or : Condition::Kind::And;
    Condition value{kind, bar, true, {}};
    for (const Arc& arc : d_.arcs) {
      if (arc.to != bar) continue;
      Condition term = arcTerm(arc);
      if (term.kind == kind) for (Condition& c : term.operands) value.operands.push_back(std::move(c));
      else value.operands.push_back(std::move(term));
    }
    // A split passes its one input on unchanged (de-grouping: each branch gets the condition).
    if (node(bar).kind == NodeKind::AndSplit) return std::move(value.operands.front());
    return value;
  }

  // The groups `c` uses, each after the groups its own value uses.
  void collectGroups(const Condition& c, std::vector<GroupDefinition>& out) const {
    for (const Condition& operand : c.operands) collectGroups(operand, out);
    if (c.kind != Condition::Kind::Group) return;
    for (const GroupDefinition& g : out)
      if (g.bar == c.node) return;
    Condition value = barValue(c.node);
    collectGroups(value, out);
    out.push_back({c.node, std::move(value)});
  }

  // One rule per source of the unit's output arcs: the arcs leaving one node share its IF.
  void addRules(size_t u, const LogicUnit& unit, std::vector<Rule>& rules) const {
    std::vector<size_t> sources;
    for (size_t a : unit.arcs)
      if (!barAt(d_.arcs[a].to)) addOnce(sources, d_.arcs[a].from);
    for (size_t i = 0; i < sources.size(); ++i) {
      Rule rule;
      rule.index = std::to_string(u + 1);
      if (sources.size() > 1) rule.index += '.' + std::to_string(i + 1);
      rule.unit = u;
      for (size_t a : unit.arcs) {
        const Arc& arc = d_.arcs[a];
        if (arc.from != sources[i] || barAt(arc.to)) continue;
        if (rule.actions.empty()) rule.condition = arcTerm(arc);
        rule.actions.push_back({arc.to, arc.kind != ArcKind::NotOut});
      }
      collectGroups(rule.condition, rule.groups);
      rules.push_back(std::move(rule));
    }
  }

  const Diagram& d_;
  std::vector<size_t> barUnit_;  // the unit of each bar; SIZE_MAX for activities
};

}  // namespace

std::string_view luTypeLabel(LuType type) { return kLuTypes[static_cast<size_t>(type)].label; }
std::string_view luTypeDescription(LuType type) { return kLuTypes[static_cast<size_t>(type)].description; }

DiagramTables decompose(const Diagram& diagram) { return Decomposer(diagram).run(); }

}  // namespace virtcom::ad
