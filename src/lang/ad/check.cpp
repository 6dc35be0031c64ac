// The structural rules of a diagram (reader.hpp, checkProgram): what must hold before it can be
// decomposed into logic units.
#include <cstdint>
#include <string>
#include <vector>

#include "lang/ad/diagnostic_codes.hpp"
#include "lang/ad/reader.hpp"

namespace virtcom::ad {

namespace {

class DiagramCheck {
 public:
  DiagramCheck(const Program& program, const Diagram& diagram, Diagnostics& diags)
      : program_(program), d_(diagram), diags_(diags), in_(diagram.nodes.size()), out_(diagram.nodes.size()) {
    for (size_t a = 0; a < d_.arcs.size(); ++a) {
      out_[d_.arcs[a].from].push_back(a);
      in_[d_.arcs[a].to].push_back(a);
    }
  }

  void run() {
    checkStart();
    for (const Arc& arc : d_.arcs) checkArc(arc);
    for (size_t n = 0; n < d_.nodes.size(); ++n) {
      if (isBar(d_.nodes[n].kind)) checkBar(n);
      if (isBlock(d_.nodes[n].kind)) checkBlockInputs(n);
    }
    checkCycles();
  }

 private:
  const Node& node(size_t n) const { return d_.nodes[n]; }
  bool isLogicArc(const Arc& arc) const { return !isTerminal(node(arc.from).kind) && !isTerminal(node(arc.to).kind); }

  void checkStart() {
    size_t starts = 0;
    for (const Node& n : d_.nodes) {
      if (n.kind != NodeKind::Start || ++starts == 1) continue;
      diags_.error(diag::A008, n.loc, "diagram '" + d_.name + "' has a second start activity '" + n.id + "'");
    }
    if (starts == 0) diags_.error(diag::A008, d_.loc, "diagram '" + d_.name + "' has no start activity");
  }

  void checkArc(const Arc& arc) {
    const Node& from = node(arc.from);
    const Node& to = node(arc.to);
    auto invalid = [&](const std::string& why) { diags_.error(diag::A007, arc.loc, why); };
    if (to.kind == NodeKind::Start) return invalid("no arc enters the start activity '" + to.id + "'");
    if (from.kind == NodeKind::Stop) return invalid("no arc leaves the stop activity '" + from.id + "'");
    if ((isTerminal(from.kind) && isBar(to.kind)) || (isBar(from.kind) && isTerminal(to.kind)))
      return invalid("start and stop connect to activities, not to logic-flow transitions");
    if (isTerminal(from.kind) || isTerminal(to.kind)) {
      if (arc.kind != ArcKind::Normal) invalid("arcs from start or to stop are normal arcs (->)");
      return;
    }
    if (arc.kind == ArcKind::NotIn && isBar(from.kind))
      return invalid("a NOT-IN arc (|->) leaves an activity (it is a normally closed contact), not '" + from.id + "'");
    if (arc.kind == ArcKind::NotOut && (isBar(to.kind) || (isBlock(to.kind) && blockInputOf(to, false).empty())))
      return invalid("a NOT-OUT arc (->|) enters an activity or a counter (reset), not '" + to.id + "'");
    if (to.kind == NodeKind::Activity && activityPortKind(program_, to) == PortKind::Input)
      diags_.error(diag::A009, arc.loc, "activity '" + to.id + "' is bound to the input '" + to.variable +
                                            "', which the logic cannot write; bind it to an O or M port");
  }

  void checkBar(size_t n) {
    const Node& bar = node(n);
    std::string what = std::string(nodeKeyword(bar.kind)) + " '" + bar.id + "'";
    if (in_[n].empty() || out_[n].empty()) {
      diags_.error(diag::A005, bar.loc, what + " has no " + (in_[n].empty() ? "incoming" : "outgoing") + " arc");
      return;
    }
    bool join = isJoin(bar.kind);
    size_t branches = join ? in_[n].size() : out_[n].size();
    size_t single = join ? out_[n].size() : in_[n].size();
    if (branches < 2)
      diags_.error(diag::A006, bar.loc, what + " has one " + (join ? "input" : "output") + "; it needs at least two");
    if (single > 1)
      diags_.error(diag::A006, bar.loc, what + " has " + std::to_string(single) + (join ? " outputs" : " inputs") +
                                            "; it has exactly one (use an and-split or a join for more)");
  }

  // A timer's IN and a counter's count input follow one condition; a counter has one reset.
  void checkBlockInputs(size_t n) {
    size_t driving = 0, resets = 0;
    for (size_t a : in_[n]) {
      const Arc& arc = d_.arcs[a];
      if (!isLogicArc(arc)) continue;
      size_t& count = arc.kind == ArcKind::NotOut ? resets : driving;
      if (++count == 2)
        diags_.error(diag::A011, arc.loc, std::string(arc.kind == ArcKind::NotOut ? "the reset" : "the input") + " of '" +
                                              node(n).id + "' is already driven by another arc; join the conditions with an or-join");
    }
  }

  bool isMemory(const Node& n) const {
    return isBlock(n.kind) || (n.kind == NodeKind::Activity && activityPortKind(program_, n) == PortKind::Memory);
  }

  // A cycle of arcs through no memory element (M activity, timer, counter) is feedback whose
  // value depends on the order of the rules. Kahn's algorithm peels every node that is on no
  // such cycle; from any node left, walking back along arcs from nodes left closes a cycle.
  void checkCycles() {
    size_t count = d_.nodes.size();
    std::vector<bool> kept(count);
    std::vector<size_t> indegree(count), ready;
    for (size_t n = 0; n < count; ++n) kept[n] = !isTerminal(node(n).kind) && !isMemory(node(n));
    for (const Arc& arc : d_.arcs)
      if (kept[arc.from] && kept[arc.to]) ++indegree[arc.to];
    for (size_t n = 0; n < count; ++n)
      if (kept[n] && indegree[n] == 0) ready.push_back(n);
    while (!ready.empty()) {
      size_t n = ready.back();
      ready.pop_back();
      kept[n] = false;
      for (size_t a : out_[n])
        if (kept[d_.arcs[a].to] && --indegree[d_.arcs[a].to] == 0) ready.push_back(d_.arcs[a].to);
    }
    for (size_t n = 0; n < count; ++n)
      if (kept[n]) return reportCycle(n, kept);
  }

  void reportCycle(size_t start, const std::vector<bool>& kept) {
    std::vector<size_t> path;            // nodes walked backwards
    std::vector<size_t> seenAt(d_.nodes.size(), SIZE_MAX);
    size_t n = start, arcIn = 0;
    while (seenAt[n] == SIZE_MAX) {
      seenAt[n] = path.size();
      path.push_back(n);
      for (size_t a : in_[n])
        if (kept[d_.arcs[a].from]) { arcIn = a; break; }
      n = d_.arcs[arcIn].from;
    }
    std::string text = node(n).id;
    for (size_t i = path.size(); i-- > seenAt[n];) text += " -> " + node(path[i]).id;  // walked backwards
    diags_.error(diag::A010, d_.arcs[arcIn].loc, "the arcs " + text + " form a cycle through no memory (an M activity, "
                                                     "a timer or a counter); route the feedback through an M port");
  }

  const Program& program_;
  const Diagram& d_;
  Diagnostics& diags_;
  std::vector<std::vector<size_t>> in_, out_;  // arc indexes by node
};

}  // namespace

void checkProgram(const Program& program, Diagnostics& diags) {
  for (const Diagram& d : program.diagrams) DiagramCheck(program, d, diags).run();
}

}  // namespace virtcom::ad
