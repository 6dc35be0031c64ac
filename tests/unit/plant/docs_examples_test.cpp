// Every ```yaml example in docs/devices.md loads without diagnostics, and every registered
// device type has a section and an example there, so the documentation cannot drift from the code.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "plant_rig.hpp"

namespace virtcom::plant::test {
namespace {

std::string readDoc() {
  std::ifstream in(std::string(VIRTCOM_SOURCE_DIR) + "/docs/devices.md");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The yaml blocks, each turned from a `- name: X` list item into a plain map.
std::vector<std::string> yamlExamples(const std::string& doc) {
  std::vector<std::string> out;
  size_t pos = 0;
  while ((pos = doc.find("```yaml\n", pos)) != std::string::npos) {
    size_t end = doc.find("```", pos + 8);
    std::istringstream block(doc.substr(pos + 8, end - pos - 8));
    std::string line, yaml;
    while (std::getline(block, line)) yaml += (line.size() >= 2 ? line.substr(2) : line) + "\n";
    out.push_back(yaml);
    pos = end + 3;
  }
  return out;
}

TEST(DocsExamples, EveryExampleLoads) {
  const std::string doc = readDoc();
  ASSERT_FALSE(doc.empty());
  auto examples = yamlExamples(doc);
  std::set<std::string> typesShown;
  for (const auto& yaml : examples) {
    PlantRig rig;
    ConfigNode n = MiniYaml::parse(yaml);
    const std::string type = n.find("type")->scalar();
    const std::string name = n.find("name")->scalar();
    typesShown.insert(type);
    EXPECT_NE(rig.add(type, name, yaml), nullptr) << yaml << rig.renderedDiags();
  }
  for (const auto& [type, description] : deviceTypes()) EXPECT_TRUE(typesShown.count(type)) << "no example of " << type;
}

TEST(DocsExamples, EveryTypeHasASection) {
  const std::string doc = readDoc();
  for (const auto& [type, description] : deviceTypes()) {
    EXPECT_NE(doc.find("\n## " + type + "\n"), std::string::npos) << type;
    EXPECT_NE(doc.find(description), std::string::npos) << type;
  }
}

}  // namespace
}  // namespace virtcom::plant::test
