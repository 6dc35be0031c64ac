#pragma once
// The layer table of docs/architecture.md (the ```layers block) and its known exceptions (the
// ```layer-exceptions block), read for tests/unit/layers: which src/ folder may include which.
// Format and meaning are documented in docs/architecture.md, "Layer table".
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "support/read_file.hpp"

namespace virtcom::layers {

struct LayerRow {
  std::vector<std::string> standsOn;  // the layers named in the row, as written
  bool planned = false;               // `[planned]`: no folder yet
  int line = 0;                       // in docs/architecture.md
};

// One accepted include against the table: `src/...` file and the header it includes.
struct LayerException {
  std::string file, header;
  int line = 0;
};

struct LayerTable {
  std::map<std::string, LayerRow> rows;
  std::vector<LayerException> exceptions;
  std::vector<std::string> errors;  // `docs/architecture.md:LINE: ...` for malformed lines
};

inline std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

inline std::string sourceDir() { return VIRTCOM_SOURCE_DIR; }

// Reads both blocks from the text of docs/architecture.md. A line `name: a, b` (a `#` starts a
// comment) is a row; `file: header` an exception. Never throws: problems go to `errors`.
inline LayerTable parseLayerTable(const std::string& doc) {
  LayerTable table;
  std::istringstream lines(doc);
  std::string raw;
  enum class Block { None, Layers, Exceptions } block = Block::None;
  for (int number = 1; std::getline(lines, raw); ++number) {
    std::string_view line = trimmed(raw);
    if (block == Block::None) {
      if (line == "```layers") block = Block::Layers;
      if (line == "```layer-exceptions") block = Block::Exceptions;
      continue;
    }
    if (line.starts_with("```")) {
      block = Block::None;
      continue;
    }
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    const auto colon = line.find(':');
    const std::string where = "docs/architecture.md:" + std::to_string(number) + ": ";
    if (colon == std::string_view::npos) {
      table.errors.push_back(where + "expected `name: ...`, got `" + std::string(line) + "`");
      continue;
    }
    const std::string name(trimmed(line.substr(0, colon)));
    std::string_view rest = trimmed(line.substr(colon + 1));
    if (block == Block::Exceptions) {
      table.exceptions.push_back({name, std::string(rest), number});
      continue;
    }
    LayerRow row;
    row.line = number;
    constexpr std::string_view kPlanned = "[planned]";
    if (rest.ends_with(kPlanned)) {
      row.planned = true;
      rest = trimmed(rest.substr(0, rest.size() - kPlanned.size()));
    }
    while (!rest.empty()) {
      const auto comma = rest.find(',');
      const std::string_view entry = trimmed(rest.substr(0, comma));
      if (!entry.empty()) row.standsOn.emplace_back(entry);
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    if (!table.rows.emplace(name, row).second) table.errors.push_back(where + "a second row for `" + name + "`");
  }
  if (table.rows.empty()) table.errors.push_back("docs/architecture.md: no ```layers block");
  return table;
}

inline LayerTable loadLayerTable() { return parseLayerTable(test::readFile(sourceDir() + "/docs/architecture.md")); }

// Everything `layer` may include besides itself: its row's layers and, transitively, theirs.
// A name without a row contributes only itself (the table test reports it).
inline std::set<std::string> allowedIncludes(const LayerTable& table, const std::string& layer) {
  std::set<std::string> reached;
  std::vector<std::string> pending{layer};
  while (!pending.empty()) {
    const std::string next = pending.back();
    pending.pop_back();
    const auto row = table.rows.find(next);
    if (row == table.rows.end()) continue;
    for (const std::string& below : row->second.standsOn)
      if (reached.insert(below).second) pending.push_back(below);
  }
  return reached;
}

inline std::string joined(const std::set<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// A folder's path below src/ ("lang/st/parse"), "" for src/ itself.
inline std::string layerOf(const std::filesystem::path& file) {
  return std::filesystem::relative(file.parent_path(), sourceDir() + "/src").generic_string();
}

// Every regular file under src/, sorted so that reports come in a stable order.
inline std::vector<std::filesystem::path> sourceTreeFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(sourceDir() + "/src"))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Files that are code (their includes are checked, their folder is a layer): all but a
// folder's README.md and CMakeLists.txt.
inline bool isCode(const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  return name != "README.md" && name != "CMakeLists.txt";
}

// "src/cell/cell.hpp" for a file of the tree.
inline std::string repoPath(const std::filesystem::path& file) {
  return std::filesystem::relative(file, sourceDir()).generic_string();
}

}  // namespace virtcom::layers
