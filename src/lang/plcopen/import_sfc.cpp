// Graphical SFC bodies: steps, macro steps, transitions, divergences/convergences, jumps and
// action blocks, connected by localId/refLocalId, into the chart model of lang/sfc, then lowered
// to ST like a textual chart. A macro step is expanded in place: its steps join the chart named
// `Macro__Step`, entered through its initial step and left through its final step.
#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/import_internal.hpp"
#include "lang/plcopen/network_translate.hpp"
#include "lang/sfc/lower.hpp"

namespace virtcom::plcopen::detail {

namespace {

// Divergences and convergences chain only a few levels deep; a bound stops cyclic junk.
constexpr int kMaxJunctionDepth = 64;
// Macro steps nest a few levels in real charts; the bound keeps a hostile file off the stack.
constexpr int kMaxMacroDepth = 16;

// The steps a macro step stands for in the enclosing chart; empty names for a malformed one
// (reported), which still counts as a step so that its transitions are not reported again.
struct MacroSteps {
  std::string entry, exit;
};

class ChartReader {
 public:
  // `prefix` names the steps of a macro step's chart ("Macro__"; empty for the POU's chart).
  ChartReader(Importer& imp, pugi::xml_node pouNode, st::Pou& pou, std::string prefix = {}, int depth = 0)
      : imp_(imp), pouNode_(pouNode), pou_(pou), prefix_(std::move(prefix)), depth_(depth) {}

  // Fills the chart; false if anything was reported.
  bool read(pugi::xml_node sfc, sfc::Chart& chart);
  // The steps marked initialStep of a macro step's chart (not initial in the enclosing chart).
  const std::vector<std::string>& entrySteps() const { return entrySteps_; }

 private:
  std::vector<uint32_t> inputsOf(pugi::xml_node node);
  sfc::NamedRef stepRef(pugi::xml_node node, std::string_view name) const {
    return {prefix_ + std::string(name), imp_.xml().at(node)};
  }
  void step(pugi::xml_node node, sfc::Chart& chart);
  void macroStep(pugi::xml_node node, sfc::Chart& chart);
  std::string jumpTarget(std::string_view name) const;
  // Junctions already walked for the current transition: shared junctions are walked once.
  using Seen = std::unordered_set<uint32_t>;
  void stepsBefore(uint32_t localId, pugi::xml_node from, std::vector<sfc::NamedRef>& out, Seen& seen, int depth);
  void stepsAfter(pugi::xml_node node, std::vector<sfc::NamedRef>& out, Seen& seen, int depth);
  void transition(pugi::xml_node node, sfc::Chart& chart);
  void condition(pugi::xml_node node, pugi::xml_node cond, sfc::Transition& t);
  void conditionText(pugi::xml_node body, sfc::Transition& t, std::string_view name);
  void wiredCondition(pugi::xml_node node, sfc::Transition& t);
  void actionBlock(pugi::xml_node node, sfc::Chart& chart);
  pugi::xml_node element(uint32_t localId) const {
    auto it = byId_.find(localId);
    return it == byId_.end() ? pugi::xml_node() : it->second;
  }
  void fail(std::string_view code, pugi::xml_node node, std::string message) {
    imp_.error(code, node, std::move(message));
    ok_ = false;
  }

  Importer& imp_;
  pugi::xml_node pouNode_;
  st::Pou& pou_;
  std::string prefix_;
  int depth_;
  std::unordered_map<uint32_t, pugi::xml_node> byId_;
  std::unordered_map<uint32_t, std::vector<pugi::xml_node>> readers_;  // localId -> elements reading it
  std::unordered_map<uint32_t, MacroSteps> macros_;                     // macro step localId -> its steps
  std::unordered_map<std::string, std::string> macroEntries_;           // macro step name -> its entry step
  std::vector<std::string> entrySteps_;
  Network network_;  // the LD/FBD elements that compute wired conditions
  bool ok_ = true;
};

std::vector<uint32_t> ChartReader::inputsOf(pugi::xml_node node) {
  std::vector<uint32_t> ids;
  for (pugi::xml_node in : children(node, "connectionPointIn"))
    for (pugi::xml_node c : children(in, "connection")) {
      std::string_view text = c.attribute("refLocalId").value();
      uint32_t id = 0;
      bool digits = !text.empty() && text.size() < 10 && std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
      if (!digits) {
        fail(diag::X005, c, "<connection> refLocalId '" + std::string(text) + "' is not a whole number");
        continue;
      }
      for (char ch : text) id = id * 10 + static_cast<uint32_t>(ch - '0');
      ids.push_back(id);
    }
  return ids;
}

void ChartReader::stepsBefore(uint32_t localId, pugi::xml_node from, std::vector<sfc::NamedRef>& out, Seen& seen,
                              int depth) {
  pugi::xml_node e = element(localId);
  if (!e) return fail(diag::X006, from, describe(from) + ": the connection refers to localId " + std::to_string(localId) + ", which is no element of this chart");
  std::string_view kind = localName(e);
  if (kind == "step") {
    out.push_back(stepRef(e, e.attribute("name").value()));
  } else if (kind == "macroStep") {
    if (auto macro = macros_.find(localId); macro != macros_.end()) out.push_back({macro->second.exit, imp_.xml().at(e)});
  } else if ((kind == "selectionDivergence" || kind == "simultaneousConvergence") && depth < kMaxJunctionDepth) {
    if (!seen.insert(localId).second) return;
    for (uint32_t id : inputsOf(e)) stepsBefore(id, e, out, seen, depth + 1);
  } else {
    fail(diag::X006, from, describe(from) + " follows " + describe(e) + "; a transition follows a step, a macro step, a selection divergence or a simultaneous convergence");
  }
}

void ChartReader::stepsAfter(pugi::xml_node node, std::vector<sfc::NamedRef>& out, Seen& seen, int depth) {
  uint32_t id = static_cast<uint32_t>(node.attribute("localId").as_uint());
  if (depth > 0 && !seen.insert(id).second) return;
  for (pugi::xml_node next : readers_[id]) {
    std::string_view kind = localName(next);
    if (kind == "step") {
      out.push_back(stepRef(next, next.attribute("name").value()));
    } else if (kind == "macroStep") {
      auto macro = macros_.find(static_cast<uint32_t>(next.attribute("localId").as_uint()));
      if (macro != macros_.end()) out.push_back({macro->second.entry, imp_.xml().at(next)});
    } else if (kind == "jumpStep") {
      out.push_back({jumpTarget(next.attribute("targetName").value()), imp_.xml().at(next)});
    } else if ((kind == "simultaneousDivergence" || kind == "selectionConvergence") && depth < kMaxJunctionDepth) {
      stepsAfter(next, out, seen, depth + 1);
    } else if (kind != "actionBlock") {
      fail(diag::X006, next, describe(next) + " follows " + describe(node) + "; a transition leads to a step, a macro step, a jump, a simultaneous divergence or a selection convergence");
    }
  }
}

// A jump to a macro step enters it through its initial step.
std::string ChartReader::jumpTarget(std::string_view name) const {
  auto macro = macroEntries_.find(std::string(name));
  return macro != macroEntries_.end() ? macro->second : prefix_ + std::string(name);
}

// The body of a named transition (<transitions> of the POU) or of an inline condition: an ST
// expression, or ST/LD/FBD statements assigning `name` (the transition's, or the inline's).
void ChartReader::conditionText(pugi::xml_node body, sfc::Transition& t, std::string_view name) {
  pugi::xml_node lang = firstElement(body);
  std::string_view kind = lang ? localName(lang) : std::string_view();
  if (kind == "ST") {
    pugi::xml_node text = firstText(lang);
    if (!text) return fail(diag::X003, body, "the transition condition is empty");
    if (std::string_view(text.value()).find(":=") == std::string_view::npos || name.empty()) {
      t.condition = imp_.expressionAt(text);
      return;
    }
    t.name = name;
    t.body = imp_.statementsAt(text);
  } else if (kind == "LD" || kind == "FBD") {
    if (name.empty())
      return fail(diag::X003, body, "an <inline> " + std::string(kind) + " condition needs a 'name': its network assigns the condition to it");
    t.name = name;
    Network net = readNetwork(imp_, lang, kind == "LD");
    t.body = translateNetwork(imp_, net, pou_, t.name + "_");
  } else {
    imp_.unsupported(lang ? lang : body, "a transition condition in <" + std::string(kind) + ">");
    ok_ = false;
  }
}

// A condition wired from LD/FBD elements of the chart: an expression, or (when the network needs
// statements first: FB calls, edge memories) a body assigning a hidden transition name. Hidden
// variables are the transition's own: two transitions may read one element.
void ChartReader::wiredCondition(pugi::xml_node node, sfc::Transition& t) {
  uint32_t id = static_cast<uint32_t>(node.attribute("localId").as_uint());
  std::string name = prefix_ + "cond" + std::to_string(id);
  st::StmtList before;
  st::ExprPtr value = translateCondition(imp_, network_, id, pou_, name + "_", before);
  if (before.empty()) {
    t.condition = std::move(value);
    return;
  }
  t.name = "__" + name;
  t.body = std::move(before);
  t.body.push_back(imp_.build().assign(imp_.build().name(t.name, t.loc), std::move(value)));
}

void ChartReader::condition(pugi::xml_node node, pugi::xml_node cond, sfc::Transition& t) {
  if (pugi::xml_node inline_ = child(cond, "inline")) {
    conditionText(inline_, t, inline_.attribute("name").value());
  } else if (pugi::xml_node ref = child(cond, "reference")) {
    t.name = ref.attribute("name").value();
    pugi::xml_node body;
    for (pugi::xml_node def : children(child(pouNode_, "transitions"), "transition"))
      if (t.name == def.attribute("name").value() && (body = child(def, "body"))) break;
    if (!body) return fail(diag::X003, ref, "transition '" + t.name + "' is not defined in the POU's <transitions>");
    conditionText(body, t, t.name);
  } else if (child(cond, "connectionPointIn")) {
    wiredCondition(node, t);
  } else {
    return fail(diag::X003, cond, "<condition> holds none of <inline>, <reference>, <connectionPointIn>");
  }
  std::string_view negated = cond.attribute("negated").value();
  if (negated != "true" && negated != "1") return;
  AstBuilder& b = imp_.build();
  if (t.condition) t.condition = b.notOf(std::move(t.condition));
  else if (!t.name.empty()) t.body.push_back(b.assign(b.name(t.name, t.loc), b.notOf(b.name(t.name, t.loc))));
}

void ChartReader::transition(pugi::xml_node node, sfc::Chart& chart) {
  sfc::Transition t;
  t.loc = imp_.xml().at(node);
  if (pugi::xml_attribute priority = node.attribute("priority")) t.priority = priority.as_llong();
  Seen before, after;
  for (uint32_t id : inputsOf(node)) stepsBefore(id, node, t.from, before, 0);
  stepsAfter(node, t.to, after, 0);
  if (t.from.empty()) fail(diag::X008, node, describe(node) + " has no preceding step");
  if (t.to.empty()) fail(diag::X008, node, describe(node) + " leads to no step");
  pugi::xml_node cond = child(node, "condition");
  if (!cond) return fail(diag::X003, node, describe(node) + " has no <condition>");
  condition(node, cond, t);
  chart.transitions.push_back(std::move(t));
}

void ChartReader::actionBlock(pugi::xml_node node, sfc::Chart& chart) {
  std::vector<uint32_t> inputs = inputsOf(node);
  pugi::xml_node stepNode = inputs.size() == 1 ? element(inputs.front()) : pugi::xml_node();
  if (!stepNode || localName(stepNode) != "step")
    return fail(diag::X006, node, describe(node) + " must be connected to exactly one step");
  std::string stepName = prefix_ + stepNode.attribute("name").value();
  auto step = std::find_if(chart.steps.begin(), chart.steps.end(), [&](const sfc::Step& s) { return s.name == stepName; });
  if (step == chart.steps.end()) return;
  for (pugi::xml_node a : children(node, "action")) {
    sfc::ActionAssociation assoc;
    assoc.loc = imp_.xml().at(a);
    std::string_view qualifier = a.attribute("qualifier").value();
    auto q = sfc::qualifierFromText(qualifier.empty() ? "N" : qualifier);
    if (!q) {
      fail(diag::X005, a, describe(a) + ": '" + std::string(qualifier) + "' is not an action qualifier (N, R, S, L, D, P, P0, P1, SD, DS, SL)");
      continue;
    }
    assoc.qualifier = *q;
    if (a.attribute("duration")) assoc.duration = imp_.expressionAt(a, "duration");
    if (sfc::qualifierNeedsTime(*q) && !assoc.duration)
      fail(diag::X003, a, "action qualifier " + std::string(qualifier) + " needs a 'duration' attribute");
    if (!sfc::qualifierNeedsTime(*q)) assoc.duration = nullptr;
    if (pugi::xml_attribute indicator = a.attribute("indicator"); indicator && *indicator.value())
      assoc.indicator = {indicator.value(), imp_.xml().at(a)};
    if (pugi::xml_node ref = child(a, "reference")) {
      assoc.action = {ref.attribute("name").value(), imp_.xml().at(ref)};
    } else if (pugi::xml_node inl = child(a, "inline")) {
      // An inline action body becomes a chart action of its own, named after the block.
      std::string name = "__" + step->name + "_action" + std::to_string(node.attribute("localId").as_uint()) + "_" +
                         std::to_string(step->actions.size());
      pugi::xml_node st = child(inl, "ST");
      pugi::xml_node text = st ? firstText(st) : pugi::xml_node();
      if (!text) {
        imp_.unsupported(firstElement(inl) ? firstElement(inl) : inl, "an inline action that is not ST");
        ok_ = false;
        continue;
      }
      chart.actions.push_back({name, imp_.xml().at(inl), imp_.statementsAt(text)});
      assoc.action = {name, imp_.xml().at(inl)};
    } else {
      fail(diag::X003, a, describe(a) + " has neither <reference> nor <inline>");
      continue;
    }
    step->actions.push_back(std::move(assoc));
  }
}

void ChartReader::step(pugi::xml_node e, sfc::Chart& chart) {
  sfc::Step step;
  std::string_view name = e.attribute("name").value();
  step.name = prefix_ + std::string(name);
  step.loc = imp_.xml().at(e, "name");
  std::string_view initial = e.attribute("initialStep").value();
  bool marked = initial == "true" || initial == "1";
  step.initial = marked && depth_ == 0;
  if (marked && depth_ > 0) entrySteps_.push_back(step.name);
  if (name.empty()) fail(diag::X003, e, describe(e) + " has no 'name' attribute");
  chart.steps.push_back(std::move(step));
}

// The macro step's chart joins this one; its initial step is the entry, and its final step (the
// one step no transition of the macro leaves) the exit.
void ChartReader::macroStep(pugi::xml_node e, sfc::Chart& chart) {
  uint32_t id = static_cast<uint32_t>(e.attribute("localId").as_uint());
  std::string name = e.attribute("name").value();
  if (name.empty()) name = "MacroStep" + std::to_string(id);
  std::string label = "macro step '" + name + "' (localId " + std::to_string(id) + ")";
  macros_[id] = {};
  pugi::xml_node body = child(child(e, "body"), "SFC");
  if (!body) return fail(diag::X012, e, label + " has no <body><SFC>: a macro step holds a chart");
  if (depth_ >= kMaxMacroDepth) {
    imp_.unsupported(e, "a macro step nested more than " + std::to_string(kMaxMacroDepth) + " deep");
    ok_ = false;
    return;
  }
  size_t firstStep = chart.steps.size(), firstTransition = chart.transitions.size();
  ChartReader inner(imp_, pouNode_, pou_, prefix_ + name + "__", depth_ + 1);
  if (!inner.read(body, chart)) {
    ok_ = false;
    return;
  }
  std::unordered_set<std::string> left;
  for (size_t k = firstTransition; k < chart.transitions.size(); ++k)
    for (const sfc::NamedRef& from : chart.transitions[k].from) left.insert(from.name);
  std::vector<std::string> finals;
  for (size_t k = firstStep; k < chart.steps.size(); ++k)
    if (!left.count(chart.steps[k].name)) finals.push_back(chart.steps[k].name);
  auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  };
  const std::vector<std::string>& entries = inner.entrySteps();
  if (entries.size() != 1)
    return fail(diag::X012, e, label + " has " + std::to_string(entries.size()) + " initial steps" +
                                   (entries.empty() ? "" : " (" + list(entries) + ")") +
                                   "; it is entered through exactly one step with initialStep=\"true\"");
  if (finals.size() != 1)
    return fail(diag::X012, e, label + " has " + std::to_string(finals.size()) + " final steps" +
                                   (finals.empty() ? "" : " (" + list(finals) + ")") +
                                   "; it is left through exactly one step that no transition of the macro step leaves");
  macros_[id] = {entries.front(), finals.front()};
  macroEntries_[name] = entries.front();
}

bool ChartReader::read(pugi::xml_node sfcNode, sfc::Chart& chart) {
  for (pugi::xml_node e = sfcNode.first_child(); e; e = e.next_sibling()) {
    if (e.type() != pugi::node_element || !e.attribute("localId")) continue;
    uint32_t id = e.attribute("localId").as_uint();
    if (!byId_.emplace(id, e).second) fail(diag::X007, e, describe(e) + ": localId " + std::to_string(id) + " is already used");
    if (!isNetworkElement(localName(e)))  // the network reader follows the connections of LD/FBD elements
      for (uint32_t in : inputsOf(e)) readers_[in].push_back(e);
  }
  if (depth_ == 0) chart.loc = imp_.xml().at(sfcNode);
  for (pugi::xml_node e = sfcNode.first_child(); e; e = e.next_sibling()) {
    if (e.type() != pugi::node_element) continue;
    std::string_view kind = localName(e);
    if (kind == "step") {
      step(e, chart);
    } else if (kind == "macroStep") {
      macroStep(e, chart);
    } else if (kind != "transition" && kind != "actionBlock" && kind != "selectionDivergence" &&
               kind != "selectionConvergence" && kind != "simultaneousDivergence" &&
               kind != "simultaneousConvergence" && kind != "jumpStep" && kind != "addData" &&
               kind != "documentation" && !isNetworkElement(kind)) {
      imp_.unsupported(e, "<" + std::string(kind) + "> in an SFC body");
      ok_ = false;
    }
  }
  network_ = readChartNetwork(imp_, sfcNode);
  for (pugi::xml_node e = sfcNode.first_child(); e; e = e.next_sibling()) {
    if (localName(e) == "transition") transition(e, chart);
    else if (localName(e) == "actionBlock") actionBlock(e, chart);
  }
  return ok_;
}

}  // namespace

void Importer::importChart(pugi::xml_node sfcNode, pugi::xml_node pouNode, st::Pou& pou) {
  if (pou.kind != st::PouKind::Program && pou.kind != st::PouKind::FunctionBlock) {
    unsupported(sfcNode, "an SFC body outside a PROGRAM or FUNCTION_BLOCK");
    return;
  }
  sfc::Chart chart;
  size_t errorsBefore = diags_.errorCount();
  if (!ChartReader(*this, pouNode, pou).read(sfcNode, chart) || diags_.errorCount() != errorsBefore) return;
  sfc::lowerChart(std::move(chart), pou, diags_, nextNodeId_);
}

}  // namespace virtcom::plcopen::detail
