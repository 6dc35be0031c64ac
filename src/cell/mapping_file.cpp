#include "cell/mapping_file.hpp"

#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cell {

ConfigNode resolveMappingFile(const ConfigNode& device, const std::filesystem::path& baseDir, SourceManager& sources,
                              Diagnostics& diags) {
  const ConfigNode* mapping = device.find("mapping");
  if (!mapping || mapping->kind() != ConfigNode::Kind::Scalar) return device;
  const std::filesystem::path file = baseDir / mapping->scalar();
  std::ifstream in(file, std::ios::binary);
  ConfigNode tree;
  bool ok = false;
  if (!in) {
    diags.error(celldiag::C002, mapping->loc(), "cannot read mapping file '" + file.string() + "'");
  } else {
    std::stringstream text;
    text << in.rdbuf();
    ok = parseYaml(file.string(), text.str(), sources, diags, tree);
  }
  // On failure the key is dropped: the problem is reported once, here.
  ConfigNode out = ConfigNode::makeMap(device.loc());
  for (const auto& [key, value] : device.entries())
    if (key != "mapping") out.add(key, device.keyLoc(key), value);
    else if (ok) out.add(key, device.keyLoc(key), tree);
  return out;
}

}  // namespace virtcom::cell
