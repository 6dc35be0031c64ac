#pragma once
// `--coverage FILE` and `--coverage-xml FILE` (docs/coverage.md), shared by `run`, `exec` and
// the scenario runner: compile with coverage probes, collect the counts after each run, merge
// them, write the lcov tracefile and Cobertura XML, print the per-POU summary.
#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <string_view>

#include "core/coverage.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::cli {

struct CoverageOptions {
  std::string lcovPath;  // --coverage: the lcov tracefile
  std::string xmlPath;   // --coverage-xml: Cobertura XML
  bool enabled() const { return !lcovPath.empty() || !xmlPath.empty(); }
  // The compile options of the PLC program: probes only when coverage was asked for.
  st::CompileOptions compileOptions(st::CompileOptions base = {}) const {
    base.coverage = enabled();
    return base;
  }
};

void addCoverageOptions(CLI::App& cmd, CoverageOptions& o);

// Writes the files asked for (the lcov test name is `testName`) and prints the summary table
// to `summary`. False, after printing "error: cannot write PATH", if a file could not be written.
bool writeCoverage(const CoverageOptions& o, const CoverageData& data, std::string_view testName, std::ostream& summary);

}  // namespace virtcom::cli
