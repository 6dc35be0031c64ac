#include "report/diagram_tables.hpp"

#include "report/html_page.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

// Every column but the index holds element ids and logic (IF, THEN, transitions), which read
// best left aligned in monospace and wrapped.
bool isLogicColumn(size_t column) { return column >= 1; }

std::string headerRow(const TextTable& table, bool withFirings) {
  std::string out = "<thead><tr>";
  for (size_t c = 0; c < table.header.size(); ++c)
    out += std::string(c == 0 ? "<th>" : "<th class=\"l\">") + escapeHtml(table.header[c]) + "</th>";
  if (withFirings) out += "<th>fired (scans)</th><th>first s</th><th>last s</th>";
  return out + "</tr></thead>";
}

std::string firingCells(const RuleFiring& f) {
  if (f.scans == 0) return "<td class=\"muted\">0</td><td class=\"muted\">\u2013</td><td class=\"muted\">\u2013</td>";
  return "<td>" + std::to_string(f.scans) + "</td><td>" + formatSeconds(f.firstNs, 3) + "</td><td>" +
         formatSeconds(f.lastNs, 3) + "</td>";
}

// `firings` is empty (no run) or has one entry per row.
std::string tableHtml(const TextTable& table, const std::vector<RuleFiring>& firings) {
  bool withFirings = !firings.empty() && firings.size() == table.rows.size();
  std::string out = "<h3>" + escapeHtml(table.title) + "</h3>\n<table class=\"rules\">" + headerRow(table, withFirings) + "<tbody>\n";
  for (size_t r = 0; r < table.rows.size(); ++r) {
    out += "<tr>";
    const std::vector<std::string>& row = table.rows[r];
    for (size_t c = 0; c < row.size(); ++c)
      out += std::string(isLogicColumn(c) ? "<td class=\"code\">" : "<td>") + escapeHtml(row[c]) + "</td>";
    if (withFirings) out += firingCells(firings[r]);
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

}  // namespace

std::string diagramTablesHtml(const std::vector<DiagramTablesSection>& sections) {
  std::string out;
  for (const DiagramTablesSection& s : sections) {
    out += "<section class=\"panel\"><h2>" + escapeHtml(s.program) + " \u00b7 " + escapeHtml(s.diagram) +
           "<span class=\"hint\">activity diagram: logic units and rules" +
           (s.firings.empty() ? "" : ", with the scans in which each rule fired") + "</span></h2>\n";
    out += tableHtml(s.lus, {}) + tableHtml(s.rules, s.firings) + "</section>\n";
  }
  return out;
}

std::string diagramTablesPage(const std::string& title, const std::vector<DiagramTablesSection>& sections) {
  return htmlPageStart(title + " \u2014 virtcom activity diagram tables") + "<header><h1>" + escapeHtml(title) +
         "</h1></header>\n<p class=\"subtitle\">LU table and rule table of each diagram (seed 002), as "
         "<code>virtcom ad tables</code> decomposes them</p>\n" +
         diagramTablesHtml(sections) + kHtmlPageEnd;
}

}  // namespace virtcom::report
