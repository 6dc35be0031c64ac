#pragma once
// Reading a program's coverage counters (docs/coverage.md).
#include <cstdint>

#include "bytecode/module.hpp"
#include "core/coverage.hpp"

namespace virtcom::bc {

// The coverage of a run: every probe of m.coverage with the count its counter holds in `memory`
// (a machine's memory image of m). Empty for a module compiled without coverage. Allocates:
// call it after the run (or between scans), never in the scan.
CoverageData collectCoverage(const Module& m, const uint8_t* memory);

}  // namespace virtcom::bc
