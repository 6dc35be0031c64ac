#pragma once
// A drive's `mapping: lib/mappings/telegram1.yaml` names a UNIVERSAL_AXIS mapping file
// (docs/universal-axis.md). The loader replaces the file name by the file's parsed tree, so the
// drive's factory reads it like an inline map and its diagnostics point into the mapping file.
#include <filesystem>

#include "core/config_node.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::cell {

// `device` unchanged unless it has a scalar `mapping:`; then a copy whose `mapping` is the tree
// of that file (relative to `baseDir`). A missing or malformed file is reported at the key.
ConfigNode resolveMappingFile(const ConfigNode& device, const std::filesystem::path& baseDir, SourceManager& sources,
                              Diagnostics& diags);

}  // namespace virtcom::cell
