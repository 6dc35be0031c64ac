// The text and XML writers of the diagram model (writer.hpp).
#include "lang/ad/writer.hpp"

#include <pugixml.hpp>

#include <sstream>

#include "core/iec_value.hpp"

namespace virtcom::ad {

namespace {

std::string_view portKindLetter(PortKind kind) {
  switch (kind) {
    case PortKind::Input: return "I";
    case PortKind::Output: return "O";
    case PortKind::Memory: return "M";
  }
  return "M";
}

std::string preset(const Node& n) {
  return n.kind == NodeKind::Timer ? formatTimeMs(n.presetNs / 1'000'000) : std::to_string(n.presetCount);
}

// The words after a node's id, in the order of its .ad line (and of its XML attributes).
std::vector<std::pair<const char*, std::string>> nodeAttributes(const Node& n) {
  switch (n.kind) {
    case NodeKind::Activity:
      if (n.variable == n.id) return {};
      return {{"variable", n.variable}};
    case NodeKind::Timer: case NodeKind::Counter:
      return {{"type", std::string(blockTypeName(n.block))}, {"preset", preset(n)}};
    case NodeKind::Block:
      if (n.blockIn == "IN" && n.blockOut == "Q") return {{"type", n.blockType}};
      return {{"type", n.blockType}, {"input", n.blockIn}, {"output", n.blockOut}};
    default: return {};
  }
}

}  // namespace

std::string formatText(const Program& program) {
  std::string out = "program " + program.name + "\n";
  for (const Port& p : program.ports) {
    out += "port " + p.name + " " + std::string(portKindLetter(p.kind));
    out += p.address.empty() ? "\n" : " " + p.address + "\n";
  }
  for (const Diagram& d : program.diagrams) {
    out += "\ndiagram " + d.name + "\n";
    for (const Node& n : d.nodes) {
      out += "  " + std::string(nodeKeyword(n.kind)) + " " + n.id;
      for (const auto& [name, value] : nodeAttributes(n)) out += " " + value;
      out += "\n";
    }
    if (!d.arcs.empty()) out += "\n";
    for (const Arc& a : d.arcs)
      out += "  " + d.nodes[a.from].id + " " + std::string(arcArrow(a.kind)) + " " + d.nodes[a.to].id + "\n";
    out += "end_diagram\n";
  }
  return out;
}

std::string formatXml(const Program& program) {
  pugi::xml_document doc;
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = doc.append_child("program");
  root.append_attribute("name") = program.name.c_str();
  for (const Port& p : program.ports) {
    pugi::xml_node port = root.append_child("port");
    port.append_attribute("name") = p.name.c_str();
    port.append_attribute("kind") = std::string(portKindLetter(p.kind)).c_str();
    if (!p.address.empty()) port.append_attribute("address") = p.address.c_str();
  }
  for (const Diagram& d : program.diagrams) {
    pugi::xml_node diagram = root.append_child("diagram");
    diagram.append_attribute("name") = d.name.c_str();
    for (const Node& n : d.nodes) {
      pugi::xml_node node = diagram.append_child(std::string(nodeKeyword(n.kind)).c_str());
      node.append_attribute("id") = n.id.c_str();
      for (const auto& [name, value] : nodeAttributes(n)) node.append_attribute(name) = value.c_str();
    }
    for (const Arc& a : d.arcs) {
      pugi::xml_node arc = diagram.append_child("arc");
      arc.append_attribute("from") = d.nodes[a.from].id.c_str();
      arc.append_attribute("to") = d.nodes[a.to].id.c_str();
      if (a.kind != ArcKind::Normal) arc.append_attribute("kind") = std::string(arcTableName(a.kind)).c_str();
    }
  }
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_indent, pugi::encoding_utf8);
  return out.str();
}

}  // namespace virtcom::ad
