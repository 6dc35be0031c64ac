#pragma once
// Reads a YAML file into a ConfigNode tree whose nodes carry file:line:col positions.
#include <string>

#include "core/config_node.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::cell {

// Parses `text` (registered in `sources` under `path`). YAML syntax errors become diagnostics
// (code C001) with their position; returns false then. Never throws.
bool parseYaml(const std::string& path, const std::string& text, SourceManager& sources, Diagnostics& diags,
               ConfigNode& out);

}  // namespace virtcom::cell
