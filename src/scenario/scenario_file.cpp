// Reading a scenario file and expanding its parameter table.
#include "scenario/scenario_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::scenario {

bool readScenarioFile(const std::string& path, SourceManager& sources, Diagnostics& diags, ScenarioFile& out) {
  out.path = path;
  out.name = std::filesystem::path(path).stem().string();
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diags.error(celldiag::C002, {}, "cannot read scenario file '" + path + "'");
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  if (!cell::parseYaml(path, text.str(), sources, diags, out.root)) return false;
  if (out.root.kind() != ConfigNode::Kind::Map) {
    diags.error(celldiag::C060, out.root.loc(), "a scenario file is a map with at least 'cell:' (docs/scenarios.md)");
    return false;
  }
  if (const ConfigNode* name = out.root.find("name"); name && name->kind() == ConfigNode::Kind::Scalar) out.name = name->scalar();
  const ConfigNode* table = out.root.find("parameters");
  if (!table) return true;
  if (table->kind() != ConfigNode::Kind::List || table->items().empty()) {
    diags.error(celldiag::C060, table->loc(), "'parameters' must be a non-empty list of rows such as {sequence: 1, max: 101 s}");
    return false;
  }
  for (const ConfigNode& row : table->items()) {
    ParameterRow values;
    if (row.kind() == ConfigNode::Kind::Map)
      for (const auto& [key, value] : row.entries())
        if (value.kind() == ConfigNode::Kind::Scalar) values.emplace_back(key, value.scalar());
    if (values.empty() || values.size() != row.entries().size()) {
      diags.error(celldiag::C060, row.loc(), "a row of 'parameters' must map names to single values, e.g. {sequence: 1, max: 101 s}");
      return false;
    }
    out.rows.push_back(std::move(values));
  }
  return true;
}

std::string caseName(const ScenarioFile& file, size_t row) {
  if (row >= file.rows.size()) return file.name;
  std::string name = file.name + "[";
  for (size_t i = 0; i < file.rows[row].size(); ++i)
    name += (i ? "," : "") + file.rows[row][i].first + "=" + file.rows[row][i].second;
  return name + "]";
}

namespace {

std::string substituteText(const std::string& text, SourceLocation loc, const ParameterRow& row, Diagnostics& diags) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t open = text.find("${", pos);
    if (open == std::string::npos) break;
    const size_t close = text.find('}', open);
    if (close == std::string::npos) break;
    out += text.substr(pos, open - pos);
    const std::string name = text.substr(open + 2, close - open - 2);
    auto found = std::find_if(row.begin(), row.end(), [&](const auto& p) { return p.first == name; });
    if (found == row.end()) {
      std::string names;
      for (const auto& [key, value] : row) names += (names.empty() ? "" : ", ") + key;
      diags.error(celldiag::C060, loc, "'${" + name + "}' names no parameter (the row has: " + (names.empty() ? "none" : names) + ")");
    } else {
      out += found->second;
    }
    pos = close + 1;
  }
  return out + text.substr(pos);
}

}  // namespace

ConfigNode substituteParameters(const ConfigNode& root, const ParameterRow& row, Diagnostics& diags) {
  switch (root.kind()) {
    case ConfigNode::Kind::Scalar: return ConfigNode::makeScalar(substituteText(root.scalar(), root.loc(), row, diags), root.loc());
    case ConfigNode::Kind::Map: {
      ConfigNode map = ConfigNode::makeMap(root.loc());
      for (const auto& [key, value] : root.entries())
        if (key != "parameters") map.add(key, root.keyLoc(key), substituteParameters(value, row, diags));
      return map;
    }
    case ConfigNode::Kind::List: {
      ConfigNode list = ConfigNode::makeList(root.loc());
      for (const ConfigNode& item : root.items()) list.push(substituteParameters(item, row, diags));
      return list;
    }
    default: return root;
  }
}

}  // namespace virtcom::scenario
