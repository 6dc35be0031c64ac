#pragma once
// Reading the cell file's `plan:` section (loader internals; the plan: core/production_plan.hpp):
// the shifts of the day and the parts each should produce, what `virtcom monitor` measures the
// plant's production against (docs/cell-file.md, "plan").
#include "cell/cell.hpp"
#include "core/config_node.hpp"

namespace virtcom::cell {

// `plan:` (null: absent, no plan) into cell.plan. Reports every mistake at its position: unknown
// keys C011, a time that is not HH:MM, parts that are not a count, a duplicate name or
// overlapping shifts C050.
void readPlanSection(Cell& cell, const ConfigNode* node, Diagnostics& diags);

}  // namespace virtcom::cell
