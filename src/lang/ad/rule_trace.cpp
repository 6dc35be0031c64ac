// Rule descriptions for --trace-rules (rule_trace.hpp).
#include "lang/ad/rule_trace.hpp"

#include "lang/ad/decompose.hpp"

namespace virtcom::ad {

namespace {

// An output as the rule writes it when it fires: the activity's variable, or the block input it
// drives (TRUE while the rule holds).
std::string thenText(const Diagram& d, const Rule& rule) {
  std::string out;
  for (const RuleAction& a : rule.actions) {
    const Node& n = d.nodes[a.node];
    if (!out.empty()) out += ", ";
    if (isBlock(n.kind)) out += n.id + "." + std::string(blockInputOf(n, a.on)) + " := TRUE";
    else out += n.variable + (a.on ? " := TRUE" : " := FALSE");
  }
  return out;
}

}  // namespace

std::vector<TracedRule> tracedRules(const Program& program) {
  std::vector<TracedRule> out;
  for (const Diagram& d : program.diagrams) {
    DiagramTables tables = decompose(d);
    for (const Rule& rule : tables.rules)
      out.push_back({d.name, rule.index, std::string(luTypeLabel(tables.units[rule.unit].type)), thenText(d, rule)});
  }
  return out;
}

}  // namespace virtcom::ad
