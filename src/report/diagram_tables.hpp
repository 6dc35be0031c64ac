#pragma once
// Activity diagrams in a report (seed 002): each diagram's LU table and rule table, in a run's
// HTML and JSON reports with how often each rule fired, or as a page of their own
// (`virtcom ad tables --format html`). The tables come as text cells from the front end
// (lang/ad/tables.hpp); the counts from plc/rule_counter.hpp, which reads them after every scan.
#include <cstdint>
#include <string>
#include <vector>

#include "core/text_table.hpp"

namespace virtcom::report {

// How often a rule fired in a run: the PLC scans in which its IF held (and it wrote its THEN),
// and the virtual times of the first and the last of them (-1 while it never fired).
struct RuleFiring {
  uint64_t scans = 0;
  int64_t firstNs = -1;
  int64_t lastNs = -1;
};

struct DiagramTablesSection {
  std::string program;  // the PROGRAM the diagram file becomes, "TankControl"
  std::string diagram;  // "Supply"
  TextTable lus;        // lang/ad luTable
  TextTable rules;      // lang/ad ruleTable
  // One per row of `rules`, in the same order, when the tables come with a run; empty otherwise.
  std::vector<RuleFiring> firings;
};

// One panel per diagram (heading "Program · diagram", the LU table, the rule table with the
// columns "fired (scans)", "first s" and "last s" when `firings` is given), names escaped; empty
// when `sections` is. Deterministic; allocates.
std::string diagramTablesHtml(const std::vector<DiagramTablesSection>& sections);

// A self-contained page with the run report's style: heading `title`, then diagramTablesHtml.
std::string diagramTablesPage(const std::string& title, const std::vector<DiagramTablesSection>& sections);

}  // namespace virtcom::report
