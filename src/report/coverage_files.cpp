#include "report/coverage_files.hpp"

#include <algorithm>
#include <tuple>

namespace virtcom::report::detail {

bool Decision::ran() const {
  return std::any_of(arms.begin(), arms.end(), [](uint64_t c) { return c > 0; });
}

namespace {

void countLine(std::map<uint32_t, uint64_t>& lines, uint32_t line, uint64_t count) {
  uint64_t& slot = lines[line];
  slot = std::max(slot, count);
}

PouLines& pouOf(FileLines& file, const std::string& name) {
  for (PouLines& p : file.pous)
    if (p.name == name) return p;
  file.pous.push_back({});
  file.pous.back().name = name;
  return file.pous.back();
}

// The POU's calls: its first statement runs once per call (ST has no jump over it); a POU
// without a statement of its own (a chart only, a diagram's rules) falls back to its busiest probe.
void finishPou(PouLines& pou, const std::vector<const CoveragePoint*>& points) {
  const CoveragePoint* first = nullptr;
  uint64_t busiest = 0;
  pou.firstLine = UINT32_MAX;
  for (const CoveragePoint* p : points) {
    pou.firstLine = std::min(pou.firstLine, p->line);
    busiest = std::max(busiest, p->count);
    if (p->kind == CoverageKind::Statement &&
        (!first || std::tie(p->line, p->column) < std::tie(first->line, first->column)))
      first = p;
  }
  pou.calls = first ? first->count : busiest;
}

}  // namespace

std::vector<FileLines> groupByFile(const CoverageData& data) {
  std::vector<FileLines> files;
  std::map<std::pair<std::string, std::string>, std::vector<const CoveragePoint*>> byPou;
  for (const CoveragePoint& p : data.points()) {  // sorted by file, line, column, kind, arm
    if (files.empty() || files.back().path != p.file) files.push_back({p.file, {}, {}});
    FileLines& file = files.back();
    PouLines& pou = pouOf(file, p.pou);
    byPou[{p.file, p.pou}].push_back(&p);
    switch (p.kind) {
      case CoverageKind::Statement: countLine(pou.lines, p.line, p.count); break;
      case CoverageKind::Step: pou.steps.push_back(&p); countLine(pou.lines, p.line, p.count); break;
      case CoverageKind::Transition: pou.transitions.push_back(&p); countLine(pou.lines, p.line, p.count); break;
      case CoverageKind::Rule: pou.rules.push_back(&p); countLine(pou.lines, p.line, p.count); break;
      case CoverageKind::Branch: {
        if (pou.decisions.empty() || pou.decisions.back().line != p.line || pou.decisions.back().column != p.column)
          pou.decisions.push_back({p.line, p.column, 0, {}});
        pou.decisions.back().arms.push_back(p.count);
        break;
      }
    }
  }
  for (FileLines& file : files) {
    for (PouLines& pou : file.pous) {
      finishPou(pou, byPou[{file.path, pou.name}]);
      for (const auto& [line, count] : pou.lines) countLine(file.lines, line, count);
    }
    std::stable_sort(file.pous.begin(), file.pous.end(),
                     [](const PouLines& a, const PouLines& b) { return a.firstLine < b.firstLine; });
    // Blocks count the decisions of one line across POUs (a line belongs to one POU anyway).
    std::map<uint32_t, uint32_t> perLine;
    for (PouLines& pou : file.pous)
      for (Decision& d : pou.decisions) d.block = perLine[d.line]++;
  }
  return files;
}

}  // namespace virtcom::report::detail
