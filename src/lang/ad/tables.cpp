// Rendering of the LU and rule tables (tables.hpp).
#include "lang/ad/tables.hpp"

#include <algorithm>
#include <cctype>

namespace virtcom::ad {

namespace {

// The seed's spelling of a bar: "OR-join", "AND-join", "AND-split".
std::string barName(NodeKind kind) {
  std::string name(nodeKeyword(kind));
  for (size_t i = 0; i < name.size() && name[i] != '-'; ++i) name[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[i])));
  return name;
}

std::string joinNames(const Diagram& d, const std::vector<size_t>& nodes) {
  std::string out;
  for (size_t n : nodes) out += (out.empty() ? "" : ", ") + d.nodes[n].id;
  return out;
}

std::string transitionText(const Diagram& d, const LogicUnit& unit) {
  if (unit.bars.empty()) return std::string(arcTableName(d.arcs[unit.arcs.front()].kind));
  std::string out;
  for (size_t b : unit.bars) out += (out.empty() ? "" : ", ") + barName(d.nodes[b].kind) + " " + d.nodes[b].id;
  std::vector<size_t> notIn, notOut;
  for (size_t a : unit.arcs) {
    const Arc& arc = d.arcs[a];
    if (arc.kind == ArcKind::NotIn) notIn.push_back(arc.from);
    if (arc.kind == ArcKind::NotOut) notOut.push_back(arc.to);
  }
  if (!notIn.empty()) out += "; NOT-IN from " + joinNames(d, notIn);
  if (!notOut.empty()) out += "; NOT-OUT to " + joinNames(d, notOut);
  return out;
}

}  // namespace

TextTable luTable(const DiagramTables& t) {
  const Diagram& d = *t.diagram;
  TextTable table{"LU table", {"index", "input activity", "transition", "output activity"}, {}};
  for (size_t u = 0; u < t.units.size(); ++u) {
    const LogicUnit& unit = t.units[u];
    table.rows.push_back({std::to_string(u + 1), joinNames(d, unit.inputs), transitionText(d, unit), joinNames(d, unit.outputs)});
  }
  return table;
}

TextTable ruleTable(const DiagramTables& t) {
  const Diagram& d = *t.diagram;
  TextTable table{"Rule table", {"index", "LU type", "IF", "THEN"}, {}};
  for (const Rule& rule : t.rules)
    table.rows.push_back({rule.index, std::string(luTypeLabel(t.units[rule.unit].type)), formatIf(d, rule), formatThen(d, rule)});
  return table;
}

namespace {

void renderText(const TextTable& table, std::string& out) {
  std::vector<size_t> width(table.header.size());
  for (size_t c = 0; c < width.size(); ++c) {
    width[c] = table.header[c].size();
    for (const auto& row : table.rows) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string text;
    for (size_t c = 0; c < cells.size(); ++c) {
      text += cells[c];
      if (c + 1 < cells.size()) text += std::string(width[c] - cells[c].size(), ' ') + " | ";
    }
    out += text + "\n";
  };
  out += table.title + "\n";
  line(table.header);
  std::string rule;
  for (size_t c = 0; c < width.size(); ++c) rule += std::string(width[c] + (c == 0 ? 1 : 2), '-') + (c + 1 < width.size() ? "+" : "");
  out += rule.substr(0, rule.size() - 1) + "\n";
  for (const auto& row : table.rows) line(row);
}

void renderMarkdown(const TextTable& table, std::string& out) {
  out += "### " + table.title + "\n\n";
  auto line = [&](const std::vector<std::string>& cells) {
    out += "|";
    for (const std::string& cell : cells) out += " " + cell + " |";
    out += "\n";
  };
  line(table.header);
  line(std::vector<std::string>(table.header.size(), "---"));
  for (const auto& row : table.rows) line(row);
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void renderCsv(const std::string& diagram, const TextTable& table, std::string& out) {
  auto line = [&](const std::string& first, const std::vector<std::string>& cells) {
    out += csvField(first);
    for (const std::string& cell : cells) {
      out += ',';
      out += csvField(cell);
    }
    out += "\n";
  };
  line("diagram", table.header);
  for (const auto& row : table.rows) line(diagram, row);
}

std::string operandText(const Diagram& d, const Condition& parent, const Condition& c) {
  bool compound = c.kind == Condition::Kind::And || c.kind == Condition::Kind::Or;
  std::string text = formatCondition(d, c);
  return compound && c.kind != parent.kind ? "(" + text + ")" : text;
}

}  // namespace

std::optional<TableFormat> tableFormatFromName(std::string_view name) {
  if (name == "text") return TableFormat::Text;
  if (name == "markdown") return TableFormat::Markdown;
  if (name == "csv") return TableFormat::Csv;
  return std::nullopt;
}

std::string formatCondition(const Diagram& d, const Condition& c) {
  switch (c.kind) {
    case Condition::Kind::Term: return d.nodes[c.node].id + (c.on ? "=on" : "=off");
    case Condition::Kind::Group: return d.nodes[c.node].id + "=on";
    default: break;
  }
  std::string out;
  for (const Condition& operand : c.operands)
    out += (out.empty() ? "" : c.kind == Condition::Kind::And ? " AND " : " OR ") + operandText(d, c, operand);
  return out;
}

std::string formatIf(const Diagram& d, const Rule& rule) {
  std::string out;
  for (const GroupDefinition& g : rule.groups)
    out += "Group " + d.nodes[g.bar].id + " := (" + formatCondition(d, g.value) + "); ";
  return out + formatCondition(d, rule.condition);
}

std::string formatThen(const Diagram& d, const Rule& rule) {
  std::string out;
  for (const RuleAction& action : rule.actions) {
    const Node& target = d.nodes[action.node];
    out += out.empty() ? "" : ", ";
    if (isBlock(target.kind)) out += target.id + "." + std::string(blockInputOf(target, action.on)) + "=on";
    else out += target.id + (action.on ? "=on" : "=off");
  }
  return out;
}

std::string formatTables(const Program& program, const std::vector<DiagramTables>& tables, TableFormat format) {
  std::string out;
  for (const DiagramTables& t : tables) {
    const Diagram& d = *t.diagram;
    TextTable lus = luTable(t), rules = ruleTable(t);
    if (!out.empty()) out += "\n";
    switch (format) {
      case TableFormat::Text:
        out += "Program " + program.name + ", diagram " + d.name + "\n\n";
        renderText(lus, out);
        out += "\n";
        renderText(rules, out);
        break;
      case TableFormat::Markdown:
        out += "## Diagram " + d.name + "\n\n";
        renderMarkdown(lus, out);
        out += "\n";
        renderMarkdown(rules, out);
        break;
      case TableFormat::Csv:
        renderCsv(d.name, lus, out);
        out += "\n";
        renderCsv(d.name, rules, out);
        break;
    }
  }
  return out;
}

}  // namespace virtcom::ad
