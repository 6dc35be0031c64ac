#include "cli/coverage_options.hpp"

#include "cli/common.hpp"
#include "report/coverage.hpp"

namespace virtcom::cli {

void addCoverageOptions(CLI::App& cmd, CoverageOptions& o) {
  cmd.add_option("--coverage", o.lcovPath,
                 "record PLC code coverage (statements, IF/CASE branches, SFC steps and transitions, activity-diagram rules) "
                 "and write it as an "
                 "lcov tracefile (genhtml makes HTML of it, see docs/coverage.md); prints a summary per POU");
  cmd.add_option("--coverage-xml", o.xmlPath, "record PLC code coverage and write it as Cobertura XML (for CI servers)");
}

bool writeCoverage(const CoverageOptions& o, const CoverageData& data, std::string_view testName, std::ostream& summary) {
  summary << report::coverageSummaryText(data);
  bool ok = true;
  if (!o.lcovPath.empty()) ok = writeFile(o.lcovPath, report::lcovTracefile(data, testName)) && ok;
  if (!o.xmlPath.empty()) ok = writeFile(o.xmlPath, report::coberturaXml(data)) && ok;
  return ok;
}

}  // namespace virtcom::cli
