#pragma once
// PLC code coverage written out (docs/coverage.md): the lcov tracefile (genhtml makes HTML of
// it), Cobertura XML (what CI servers display) and the per-POU summary of the terminal. Pure
// functions of the merged CoverageData; deterministic text.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/coverage.hpp"

namespace virtcom::report {

// Hit / total of one kind of coverage item.
struct CoverageRatio {
  uint32_t hit = 0;
  uint32_t total = 0;
  void add(bool isHit) { hit += isHit ? 1u : 0u; ++total; }
};

// One POU's coverage: statement lines, IF/CASE arms, SFC steps and transitions, activity-diagram
// rules.
struct PouCoverage {
  std::string pou;
  std::string file;
  CoverageRatio lines, branches, steps, transitions, rules;
};

// Per POU, in order of file then first line; a last row "total" over all of them.
std::vector<PouCoverage> coverageByPou(const CoverageData& data);

// The lcov tracefile (geninfo(1) format): per source file TN, SF, FN/FNDA per POU (its calls:
// the count of its first statement), FNF/FNH, BRDA per IF/CASE arm (block: the decision's rank
// among those of its line, '-' when the decision never ran), BRF/BRH, DA per line of a
// statement, step, transition or activity-diagram rule (the largest count on the line), LF/LH,
// end_of_record.
std::string lcovTracefile(const CoverageData& data, std::string_view testName);

// Cobertura XML (coverage-04.dtd): a package per source directory, a class per POU (with its
// file), a line per counted line; lines with IF/CASE arms carry branch="true" and
// condition-coverage="50% (1/2)". No timestamp: the same runs give the same bytes.
std::string coberturaXml(const CoverageData& data);

// The terminal table: per POU lines, branches, steps and transitions hit / total, and a total;
// a rules column too when the program has activity-diagram rules.
std::string coverageSummaryText(const CoverageData& data);

}  // namespace virtcom::report
