#include "lang/ad/dot.hpp"

#include "core/iec_value.hpp"

namespace virtcom::ad {

namespace {

// A DOT double-quoted string; a line break becomes DOT's centred `\n`.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

char portKindLetter(PortKind kind) {
  switch (kind) {
    case PortKind::Input: return 'I';
    case PortKind::Output: return 'O';
    case PortKind::Memory: return 'M';
  }
  return '?';
}

// An activity shows its id and, below, the signal it is bound to with the port kind; an
// outside variable (another file's) has no kind.
std::string activityLabel(const Program& program, const Node& n) {
  const std::string& signal = n.variable.empty() ? n.id : n.variable;
  std::string kind;
  if (std::optional<PortKind> k = activityPortKind(program, n)) kind = std::string(" (") + portKindLetter(*k) + ")";
  return n.id + "\n" + signal + kind;
}

std::string blockLabel(const Node& n) {
  std::string preset = isTimerBlock(n.block) ? formatTimeMs(n.presetNs / 1'000'000) : std::to_string(n.presetCount);
  return n.id + "\n" + std::string(blockTypeName(n.block)) + " " + preset;
}

// The attributes drawing one element with the seed's symbol.
std::string nodeAttributes(const Program& program, const Node& n) {
  switch (n.kind) {
    case NodeKind::Start:
      return "shape=circle, style=filled, fillcolor=black, width=0.25, fixedsize=true, label=\"\", xlabel=" + quoted(n.id);
    case NodeKind::Stop:
      return "shape=point, width=0.2, peripheries=2, label=\"\", xlabel=" + quoted(n.id);
    case NodeKind::Activity:
      return "shape=box, style=rounded, label=" + quoted(activityLabel(program, n));
    case NodeKind::Timer:
    case NodeKind::Counter:
      return "shape=box, peripheries=2, label=" + quoted(blockLabel(n));
    case NodeKind::AndJoin:
    case NodeKind::AndSplit:
      // a bar, its id written inside it (outside labels land next to the wrong bar)
      return "shape=box, style=filled, fillcolor=black, fontcolor=white, fontsize=8, height=0.16, width=1.2, "
             "fixedsize=true, label=" + quoted(n.id);
    case NodeKind::OrJoin:
      return "shape=diamond, width=0.35, height=0.35, fixedsize=true, label=\"\", xlabel=" + quoted(n.id);
  }
  return "";
}

// NOT-IN: the bar at the source end (a normally closed contact); NOT-OUT: at the target end,
// between the arrowhead and the node, as the seed draws `->|` (a negated coil).
std::string arcAttributes(ArcKind kind) {
  switch (kind) {
    case ArcKind::Normal: return "arrowhead=normal";
    case ArcKind::NotIn: return "dir=both, arrowtail=tee, arrowhead=normal";
    case ArcKind::NotOut: return "arrowhead=teenormal";
  }
  return "";
}

std::string elementName(const Diagram& d, const std::string& id) { return d.name + "." + id; }

void appendCluster(const Program& program, const Diagram& d, std::string& out) {
  out += "  subgraph " + quoted("cluster_" + d.name) + " {\n";
  out += "    id=" + quoted(d.name) + "; label=" + quoted(d.name) + ";\n";
  for (const Node& n : d.nodes) {
    const std::string name = elementName(d, n.id);
    out += "    " + quoted(name) + " [id=" + quoted(name) + ", " + nodeAttributes(program, n) + "];\n";
  }
  for (size_t i = 0; i < d.arcs.size(); ++i) {
    const Arc& a = d.arcs[i];
    out += "    " + quoted(elementName(d, d.nodes[a.from].id)) + " -> " + quoted(elementName(d, d.nodes[a.to].id)) +
           " [id=" + quoted(d.name + ".arc" + std::to_string(i + 1)) + ", " + arcAttributes(a.kind) + "];\n";
  }
  out += "  }\n";
}

}  // namespace

std::string toDot(const Program& program, const std::vector<const Diagram*>& diagrams) {
  std::string out = "digraph " + quoted(program.name) + " {\n";
  out += "  rankdir=TB; newrank=true; forcelabels=true; nodesep=0.35; ranksep=0.35;\n";
  out += "  fontname=\"Helvetica\"; node [fontname=\"Helvetica\", fontsize=11]; edge [arrowsize=0.8];\n";
  for (const Diagram* d : diagrams) appendCluster(program, *d, out);
  return out + "}\n";
}

}  // namespace virtcom::ad
