// A chart (lang/sfc model, kept on the POU by the lowering) written as a graphical TC6 <SFC>
// body, the inverse of import_sfc.cpp: what the importer reads back is the same chart.
#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/ascii.hpp"
#include "lang/plcopen/export_internal.hpp"
#include "lang/syntax/printer.hpp"

namespace virtcom::plcopen::detail {

namespace {

// A transition keeps its name (a <transitions> entry the condition references) unless it has
// none, or its condition reads like statements to the importer (a named call argument `:=`).
bool namedTransition(const sfc::Transition& t) {
  if (t.name.empty()) return false;
  return !t.condition || st::printExpr(*t.condition).find(":=") == std::string::npos;
}

class ChartWriter {
 public:
  ChartWriter(pugi::xml_node sfc, const sfc::Chart& chart) : sfc_(sfc), chart_(chart) {}

  void run() {
    assignIds();
    routeTransitions();
    for (size_t k = 0; k < chart_.steps.size(); ++k)
      if (incoming_[k].size() > 1) selConv_[k] = newId();
    for (size_t k = 0; k < chart_.steps.size(); ++k) step(k);
    for (size_t t = 0; t < chart_.transitions.size(); ++t) transition(t);
    for (size_t k = 0; k < chart_.steps.size(); ++k)
      if (selConv_[k]) junction("selectionConvergence", selConv_[k], incoming_[k], 1);
    for (const Jump& j : jumps_) {
      pugi::xml_node e = element("jumpStep", j.id, 0);
      e.append_attribute("targetName") = chart_.steps[j.target].name.c_str();
      connect(e.append_child("connectionPointIn"), j.from);
    }
  }

 private:
  struct Jump {
    uint32_t id;
    uint32_t from;
    size_t target;
  };

  void assignIds() {
    size_t steps = chart_.steps.size(), transitions = chart_.transitions.size();
    stepId_.resize(steps);
    actionsId_.resize(steps);
    selDiv_.resize(steps);
    selConv_.resize(steps);
    outgoing_.resize(steps);
    incoming_.resize(steps);
    for (size_t t = 0; t < transitions; ++t)
      for (const auto& ref : chart_.transitions[t].from)
        if (size_t k = stepIndex(ref.name); k < steps) outgoing_[k].push_back(t);
    for (size_t k = 0; k < steps; ++k) {
      stepId_[k] = newId();
      if (!chart_.steps[k].actions.empty()) actionsId_[k] = newId();
      if (outgoing_[k].size() > 1) selDiv_[k] = newId();
    }
    for (size_t t = 0; t < transitions; ++t) {
      transitionId_.push_back(newId());
      simConv_.push_back(chart_.transitions[t].from.size() > 1 ? newId() : 0);
      simDiv_.push_back(chart_.transitions[t].to.size() > 1 ? newId() : 0);
    }
  }

  // Where each transition leads: a step declared after all its source steps is entered from
  // above (several such branches meet in a selection convergence), any other through a jump.
  void routeTransitions() {
    for (size_t t = 0; t < chart_.transitions.size(); ++t) {
      const sfc::Transition& tr = chart_.transitions[t];
      size_t lastSource = 0;
      for (const auto& ref : tr.from) lastSource = std::max(lastSource, stepIndex(ref.name));
      uint32_t out = simDiv_[t] ? simDiv_[t] : transitionId_[t];
      for (const auto& ref : tr.to) {
        size_t k = stepIndex(ref.name);
        if (k >= chart_.steps.size()) continue;
        if (k > lastSource) incoming_[k].push_back(out);
        else jumps_.push_back({newId(), out, k});
      }
    }
  }

  size_t stepIndex(const std::string& name) const {
    for (size_t k = 0; k < chart_.steps.size(); ++k)
      if (iequalsAscii(chart_.steps[k].name, name)) return k;
    return chart_.steps.size();
  }
  // The point a step's outgoing transitions connect to: the step, or its selection divergence.
  uint32_t stepOutput(const std::string& name) const {
    size_t k = stepIndex(name);
    if (k >= chart_.steps.size()) return 0;
    return selDiv_[k] ? selDiv_[k] : stepId_[k];
  }

  uint32_t newId() { return ++lastId_; }

  // Elements go down the page in document order; action blocks to the right of their step.
  pugi::xml_node element(const char* kind, uint32_t id, int column) {
    pugi::xml_node e = sfc_.append_child(kind);
    e.append_attribute("localId") = id;
    pugi::xml_node position = e.append_child("position");
    position.append_attribute("x") = 100 + 200 * column;
    position.append_attribute("y") = 40 + 60 * row_;
    if (column == 0) ++row_;
    return e;
  }
  static void connect(pugi::xml_node in, uint32_t from) { in.append_child("connection").append_attribute("refLocalId") = from; }

  // A divergence or convergence: `ins` inputs, `outs` outputs (the schema names the outputs of
  // a divergence, not those of a convergence).
  void junction(const char* kind, uint32_t id, const std::vector<uint32_t>& ins, size_t outs) {
    pugi::xml_node e = element(kind, id, 0);
    for (uint32_t from : ins) connect(e.append_child("connectionPointIn"), from);
    bool divergence = std::string_view(kind).ends_with("Divergence");
    for (size_t k = 0; k < outs; ++k) {
      pugi::xml_node out = e.append_child("connectionPointOut");
      if (divergence) out.append_attribute("formalParameter") = "";
    }
  }

  void step(size_t k) {
    const sfc::Step& s = chart_.steps[k];
    pugi::xml_node e = element("step", stepId_[k], 0);
    e.append_attribute("name") = s.name.c_str();
    e.append_attribute("initialStep") = s.initial ? "true" : "false";
    if (incoming_[k].size() == 1) connect(e.append_child("connectionPointIn"), incoming_[k].front());
    if (selConv_[k]) connect(e.append_child("connectionPointIn"), selConv_[k]);
    if (!outgoing_[k].empty()) e.append_child("connectionPointOut").append_attribute("formalParameter") = "";
    if (!s.actions.empty()) {
      e.append_child("connectionPointOutAction").append_attribute("formalParameter") = "";
      actionBlock(k);
    }
    if (selDiv_[k]) junction("selectionDivergence", selDiv_[k], {stepId_[k]}, outgoing_[k].size());
  }

  bool isChartAction(const std::string& name) const {
    return std::any_of(chart_.actions.begin(), chart_.actions.end(),
                       [&](const sfc::Action& a) { return iequalsAscii(a.name, name); });
  }

  void actionBlock(size_t k) {
    pugi::xml_node block = element("actionBlock", actionsId_[k], 1);
    connect(block.append_child("connectionPointIn"), stepId_[k]);
    for (const sfc::ActionAssociation& assoc : chart_.steps[k].actions) {
      pugi::xml_node a = block.append_child("action");
      a.append_attribute("localId") = newId();
      a.append_attribute("qualifier") = std::string(sfc::qualifierSpelling(assoc.qualifier)).c_str();
      if (assoc.duration) a.append_attribute("duration") = st::printExpr(*assoc.duration).c_str();
      if (!assoc.indicator.name.empty()) a.append_attribute("indicator") = assoc.indicator.name.c_str();
      pugi::xml_node rel = a.append_child("relPosition");
      rel.append_attribute("x") = 0;
      rel.append_attribute("y") = 0;
      if (!isChartAction(assoc.action.name)) {
        a.append_child("reference").append_attribute("name") = assoc.action.name.c_str();
        continue;
      }
      for (const sfc::Action& body : chart_.actions)
        if (iequalsAscii(body.name, assoc.action.name))
          writeStText(a.append_child("inline").append_child("ST"), st::printStatements(body.body));
    }
  }

  void transition(size_t t) {
    const sfc::Transition& tr = chart_.transitions[t];
    std::vector<uint32_t> sources;
    for (const auto& ref : tr.from) sources.push_back(stepOutput(ref.name));
    if (simConv_[t]) junction("simultaneousConvergence", simConv_[t], sources, 1);
    pugi::xml_node e = element("transition", transitionId_[t], 0);
    if (tr.priority) e.append_attribute("priority") = static_cast<long long>(*tr.priority);
    connect(e.append_child("connectionPointIn"), simConv_[t] ? simConv_[t] : sources.front());
    e.append_child("connectionPointOut");
    pugi::xml_node condition = e.append_child("condition");
    if (namedTransition(tr)) {
      condition.append_child("reference").append_attribute("name") = tr.name.c_str();
    } else {
      pugi::xml_node inl = condition.append_child("inline");
      inl.append_attribute("name") = "";
      writeStText(inl.append_child("ST"), st::printExpr(*tr.condition));
    }
    if (simDiv_[t]) junction("simultaneousDivergence", simDiv_[t], {transitionId_[t]}, tr.to.size());
  }

  pugi::xml_node sfc_;
  const sfc::Chart& chart_;
  uint32_t lastId_ = 0;
  int row_ = 0;
  std::vector<uint32_t> stepId_, actionsId_, selDiv_, selConv_;     // per step (0: none)
  std::vector<uint32_t> transitionId_, simConv_, simDiv_;          // per transition (0: none)
  std::vector<std::vector<size_t>> outgoing_;                       // per step: transitions leaving it
  std::vector<std::vector<uint32_t>> incoming_;                     // per step: points entering it from above
  std::vector<Jump> jumps_;
};

}  // namespace

void writeChartTransitions(pugi::xml_node pou, const sfc::Chart& chart) {
  pugi::xml_node list;
  for (const sfc::Transition& t : chart.transitions) {
    if (!namedTransition(t)) continue;
    if (!list) list = pou.append_child("transitions");
    pugi::xml_node def = list.append_child("transition");
    def.append_attribute("name") = t.name.c_str();
    std::string text = t.condition ? st::printExpr(*t.condition) : st::printStatements(t.body);
    writeStText(def.append_child("body").append_child("ST"), text);
  }
}

void writeChartBody(pugi::xml_node pou, const sfc::Chart& chart) {
  ChartWriter(pou.append_child("body").append_child("SFC"), chart).run();
}

}  // namespace virtcom::plcopen::detail
