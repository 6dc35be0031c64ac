// Rule tables as ladder rungs (ladder.hpp).
#include "lang/ad/ladder.hpp"

#include <string>

#include "core/iec_value.hpp"

namespace virtcom::ad {

namespace {

// The BOOL a contact on this activity reads: a timer or counter is on while its Q is.
std::string stateVariable(const Node& n) {
  return isBlock(n.kind) ? n.id + "." + std::string(blockOutputOf(n)) : n.variable;
}

st::LadderCondition contacts(const Diagram& d, const Condition& c) {
  using Kind = st::LadderCondition::Kind;
  st::LadderCondition out;
  switch (c.kind) {
    case Condition::Kind::Term:
      out.variable = stateVariable(d.nodes[c.node]);
      out.negated = !c.on;
      return out;
    case Condition::Kind::Group:
      out.variable = d.nodes[c.node].id;
      return out;
    case Condition::Kind::And: out.kind = Kind::Series; break;
    case Condition::Kind::Or: out.kind = Kind::Parallel; break;
  }
  for (const Condition& operand : c.operands) out.operands.push_back(contacts(d, operand));
  return out;
}

st::LadderOutput output(const Node& target, bool on) {
  using Kind = st::LadderOutput::Kind;
  st::LadderOutput out;
  if (!isBlock(target.kind)) {
    out.kind = on ? Kind::SetCoil : Kind::ResetCoil;
    out.variable = target.variable;
    return out;
  }
  if (!on) {  // a counter's RESET / LOAD follows the rule every scan
    out.variable = target.id + "." + std::string(blockInputOf(target, false));
    return out;
  }
  out.kind = Kind::Block;
  out.variable = target.id;
  out.blockType = blockTypeOf(target);
  out.powerInput = blockInputOf(target, true);
  out.stateOutput = blockOutputOf(target);
  if (target.kind == NodeKind::Timer) {
    out.constantInput = "PT";
    out.constantValue = formatTimeMs(target.presetNs / 1'000'000);
  } else if (target.kind == NodeKind::Counter) {
    out.constantInput = "PV";
    out.constantValue = std::to_string(target.presetCount);
  }
  return out;
}

}  // namespace

st::Ladder ladderOf(const Diagram& diagram, const DiagramTables& tables) {
  st::Ladder ladder;
  for (const Rule& rule : tables.rules) {
    for (const GroupDefinition& g : rule.groups) {
      const Node& bar = diagram.nodes[g.bar];
      st::LadderOutput coil;
      coil.variable = bar.id;
      ladder.rungs.push_back({"Group " + bar.id, contacts(diagram, g.value), {coil}});
    }
    st::LadderRung rung{"Rule " + rule.index, contacts(diagram, rule.condition), {}};
    // Coils first, then blocks: the order of the ST lowering's writes.
    for (bool blocks : {false, true})
      for (const RuleAction& a : rule.actions)
        if (isBlock(diagram.nodes[a.node].kind) == blocks) rung.outputs.push_back(output(diagram.nodes[a.node], a.on));
    ladder.rungs.push_back(std::move(rung));
  }
  return ladder;
}

}  // namespace virtcom::ad
