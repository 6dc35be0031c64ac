#pragma once
// The plan a monitored plant is measured against (the cell file's `plan:` section,
// docs/cell-file.md): shifts of the wall-clock day, each with the parts it should produce.
// A description only: the cell loader fills it, report/production.hpp counts against it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/source.hpp"

namespace virtcom {

struct PlannedShift {
  std::string name;
  int32_t startMin = 0;  // local time of day, minutes since midnight
  int32_t endMin = 0;    // <= startMin: the shift ends the next day (a night shift)
  uint32_t parts = 0;    // planned production of the whole shift
  SourceLocation loc;    // the shift's entry, for messages
};

struct ProductionPlan {
  std::vector<PlannedShift> shifts;  // in file order; they never overlap (checked by the loader)
};

}  // namespace virtcom
