#include "cell/yaml_config.hpp"

#include <yaml-cpp/yaml.h>

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cell {

namespace {

SourceLocation at(uint32_t fileId, const YAML::Mark& m) {
  return {fileId, static_cast<uint32_t>(m.line + 1), static_cast<uint32_t>(m.column + 1)};
}

ConfigNode convert(const YAML::Node& node, uint32_t fileId) {
  SourceLocation loc = at(fileId, node.Mark());
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return ConfigNode::makeScalar(node.Scalar(), loc);
    case YAML::NodeType::Sequence: {
      ConfigNode list = ConfigNode::makeList(loc);
      for (const auto& item : node) list.push(convert(item, fileId));
      return list;
    }
    case YAML::NodeType::Map: {
      ConfigNode map = ConfigNode::makeMap(loc);
      for (const auto& kv : node)
        map.add(kv.first.Scalar(), at(fileId, kv.first.Mark()), convert(kv.second, fileId));
      return map;
    }
    default: return ConfigNode::makeScalar("", loc);
  }
}

}  // namespace

bool parseYaml(const std::string& path, const std::string& text, SourceManager& sources, Diagnostics& diags,
               ConfigNode& out) {
  uint32_t fileId = sources.addFile(path, text);
  try {
    YAML::Node root = YAML::Load(text);
    out = convert(root, fileId);
    return true;
  } catch (const YAML::Exception& e) {
    diags.error(celldiag::C001, at(fileId, e.mark), "YAML syntax error: " + e.msg);
    return false;
  }
}

}  // namespace virtcom::cell
