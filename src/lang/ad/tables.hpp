#pragma once
// The LU table and the rule table of seed 002 as text (`virtcom ad tables`).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/text_table.hpp"
#include "lang/ad/decompose.hpp"

namespace virtcom::ad {

enum class TableFormat : uint8_t { Text, Markdown, Csv };

// "text", "markdown", "csv"; nullopt for anything else (HTML is report/'s: cli/cmd_ad.cpp).
std::optional<TableFormat> tableFormatFromName(std::string_view name);

// How a rule's IF and THEN read in the tables (`Group K := (C1=on OR L=on); K=on AND M=on`,
// `Valve=on, Fill.IN=on`).
std::string formatCondition(const Diagram& d, const Condition& c);
std::string formatIf(const Diagram& d, const Rule& rule);
std::string formatThen(const Diagram& d, const Rule& rule);

// The seed's two tables of a decomposed diagram as cells: "LU table" (index | input activity |
// transition | output activity) and "Rule table" (index | LU type | IF | THEN), one row per unit
// and per rule, in firing order. Allocates.
TextTable luTable(const DiagramTables& tables);
TextTable ruleTable(const DiagramTables& tables);

// Both tables of every diagram of the program, in the given format. Text aligns columns;
// Markdown gives one `##` section per diagram; CSV gives one block per table whose first column
// is the diagram, blocks separated by an empty line. Allocates; never fails.
std::string formatTables(const Program& program, const std::vector<DiagramTables>& tables, TableFormat format);

}  // namespace virtcom::ad
