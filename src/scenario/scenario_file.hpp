#pragma once
// A scenario file (docs/scenarios.md) as YAML with positions, and its cases: one per row of its
// `parameters:` table (the row's values substituted for `${name}` in every scalar), or one.
#include <string>
#include <utility>
#include <vector>

#include "core/config_node.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::scenario {

using ParameterRow = std::vector<std::pair<std::string, std::string>>;  // name, value (file order)

struct ScenarioFile {
  std::string path;
  std::string name;                // `name:`, else the file name without .yaml
  ConfigNode root;
  std::vector<ParameterRow> rows;  // empty: no `parameters:`
};

// Reads `path` into `out` (YAML errors C001, a bad `parameters:` table C060). False on an error.
bool readScenarioFile(const std::string& path, SourceManager& sources, Diagnostics& diags, ScenarioFile& out);

// The test name of row `row` of `file` ("press error[code=90]"); the file's name without rows.
std::string caseName(const ScenarioFile& file, size_t row);

// `root` with `${NAME}` in every scalar replaced by the row's value (C060 for a name the row
// lacks), keeping every node's position.
ConfigNode substituteParameters(const ConfigNode& root, const ParameterRow& row, Diagnostics& diags);

}  // namespace virtcom::scenario
