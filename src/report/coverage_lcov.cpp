// The lcov tracefile and the terminal summary (report/coverage.hpp).
#include <string>

#include "report/coverage.hpp"
#include "report/coverage_files.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

using detail::FileLines;
using detail::PouLines;

namespace {

// lcov separates fields with ',' and names end the line: keep a name to one line.
std::string lcovName(std::string_view s) {
  std::string out = sanitizeUtf8(s);
  for (char& c : out)
    if (c == '\n' || c == '\r' || c == ',') c = '_';
  return out;
}

void fileRecord(std::string& out, const FileLines& file, std::string_view testName) {
  out += "TN:" + lcovName(testName) + "\nSF:" + sanitizeUtf8(file.path) + "\n";
  uint32_t fnHit = 0;
  for (const PouLines& pou : file.pous) out += "FN:" + std::to_string(pou.firstLine) + "," + lcovName(pou.name) + "\n";
  for (const PouLines& pou : file.pous) {
    out += "FNDA:" + std::to_string(pou.calls) + "," + lcovName(pou.name) + "\n";
    fnHit += pou.calls > 0 ? 1u : 0u;
  }
  out += "FNF:" + std::to_string(file.pous.size()) + "\nFNH:" + std::to_string(fnHit) + "\n";
  CoverageRatio branches;
  for (const PouLines& pou : file.pous)
    for (const detail::Decision& d : pou.decisions)
      for (size_t arm = 0; arm < d.arms.size(); ++arm) {
        out += "BRDA:" + std::to_string(d.line) + "," + std::to_string(d.block) + "," + std::to_string(arm) + "," +
               (d.ran() ? std::to_string(d.arms[arm]) : std::string("-")) + "\n";
        branches.add(d.arms[arm] > 0);
      }
  out += "BRF:" + std::to_string(branches.total) + "\nBRH:" + std::to_string(branches.hit) + "\n";
  CoverageRatio lines;
  for (const auto& [line, count] : file.lines) {
    out += "DA:" + std::to_string(line) + "," + std::to_string(count) + "\n";
    lines.add(count > 0);
  }
  out += "LF:" + std::to_string(lines.total) + "\nLH:" + std::to_string(lines.hit) + "\nend_of_record\n";
}

std::string ratioText(const CoverageRatio& r) {
  if (r.total == 0) return "-";
  return std::to_string(r.hit) + "/" + std::to_string(r.total) + " " +
         formatFixed(100.0 * r.hit / r.total, 1) + "%";
}

void addTo(PouCoverage& total, const PouCoverage& p) {
  for (auto [into, from] : {std::pair{&total.lines, &p.lines}, {&total.branches, &p.branches},
                            {&total.steps, &p.steps}, {&total.transitions, &p.transitions},
                            {&total.rules, &p.rules}}) {
    into->hit += from->hit;
    into->total += from->total;
  }
}

}  // namespace

std::vector<PouCoverage> coverageByPou(const CoverageData& data) {
  std::vector<PouCoverage> rows;
  PouCoverage total;
  total.pou = "total";
  for (const FileLines& file : detail::groupByFile(data)) {
    for (const PouLines& pou : file.pous) {
      PouCoverage row;
      row.pou = pou.name;
      row.file = file.path;
      for (const auto& [line, count] : pou.lines) row.lines.add(count > 0);
      for (const detail::Decision& d : pou.decisions)
        for (uint64_t c : d.arms) row.branches.add(c > 0);
      for (const CoveragePoint* p : pou.steps) row.steps.add(p->count > 0);
      for (const CoveragePoint* p : pou.transitions) row.transitions.add(p->count > 0);
      for (const CoveragePoint* p : pou.rules) row.rules.add(p->count > 0);
      addTo(total, row);
      rows.push_back(std::move(row));
    }
  }
  rows.push_back(std::move(total));
  return rows;
}

std::string lcovTracefile(const CoverageData& data, std::string_view testName) {
  std::string out;
  for (const FileLines& file : detail::groupByFile(data)) fileRecord(out, file, testName);
  return out;
}

std::string coverageSummaryText(const CoverageData& data) {
  const std::vector<PouCoverage> rows = coverageByPou(data);
  size_t width = 8;  // "Coverage"
  for (const PouCoverage& r : rows) width = std::max(width, displayWidth(r.pou));
  width = std::min<size_t>(width, 40);
  constexpr size_t kColumn = 18;
  const bool rules = rows.back().rules.total > 0;  // the total row: any rule at all
  std::string out = padRight("Coverage", width) + "  " + padRight("lines", kColumn) + padRight("branches", kColumn) +
                    padRight("steps", kColumn) + (rules ? padRight("transitions", kColumn) + "rules" : "transitions") + "\n";
  for (const PouCoverage& r : rows) {
    out += padRight(fitWidth(r.pou, width), width) + "  " + padRight(ratioText(r.lines), kColumn) +
           padRight(ratioText(r.branches), kColumn) + padRight(ratioText(r.steps), kColumn);
    out += rules ? padRight(ratioText(r.transitions), kColumn) + ratioText(r.rules) : ratioText(r.transitions);
    out += "\n";
  }
  return out;
}

}  // namespace virtcom::report
