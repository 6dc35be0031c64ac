#pragma once
// Internal to src/report: coverage points grouped as the writers need them (by file and POU,
// lines with their counts, decisions with their arms). Built once per write; not a hot path.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/coverage.hpp"

namespace virtcom::report::detail {

// One IF/CASE: its arms' counts in arm order.
struct Decision {
  uint32_t line = 0;
  uint32_t column = 0;
  uint32_t block = 0;  // rank among the decisions of its line
  std::vector<uint64_t> arms;
  bool ran() const;
};

struct PouLines {
  std::string name;
  uint32_t firstLine = 0;
  uint64_t calls = 0;                   // count of its first statement (or its busiest probe)
  std::map<uint32_t, uint64_t> lines;   // statement, step, transition and rule lines: largest count
  std::vector<Decision> decisions;      // by line, then column
  std::vector<const CoveragePoint*> steps, transitions, rules;
};

struct FileLines {
  std::string path;
  std::vector<PouLines> pous;           // by first line
  std::map<uint32_t, uint64_t> lines;   // all POUs' lines of the file
};

std::vector<FileLines> groupByFile(const CoverageData& data);

}  // namespace virtcom::report::detail
