#pragma once
// A test run over many scenario files (`virtcom test`): finding them, expanding their parameter
// rows, filtering by name, and running the cases on worker threads.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "scenario/runner.hpp"

namespace virtcom::scenario {

// The cases of PATHS in a stable order: a file as given; a directory's *.yaml and *.yml files
// (recursively, sorted by path). Cases whose name or file path matches `filter` (a glob with `*`
// and `?`; empty: all). A file that cannot be read or parsed still yields one case, which reports
// why when run. Sets `error` (and returns nothing) for a path that does not exist.
std::vector<CaseSpec> collectCases(const std::vector<std::string>& paths, const std::string& filter, std::string& error);

// True if `text` matches `pattern`, where `*` matches any run of characters and `?` one.
bool globMatches(std::string_view pattern, std::string_view text);

// Runs every case on `jobs` threads (at least 1); `done` is called on the calling thread once per
// case, in the order of `cases` whatever order they finish in, as soon as it and every earlier
// case have finished.
void runCases(const std::vector<CaseSpec>& cases, unsigned jobs, const CaseOptions& options,
              const std::function<void(CaseResult& result)>& done);

}  // namespace virtcom::scenario
