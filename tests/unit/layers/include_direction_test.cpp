// Dependencies only downward: every `#include "..."` under src/ against the layer table of
// docs/architecture.md, and the table against the src/ tree (a row and a README.md for every
// folder that holds code, a folder for every row, no cycle).
#include <gtest/gtest.h>

#include <regex>

#include "layer_table.hpp"

namespace virtcom::layers {
namespace {

// The layers (folders below src/) that hold code, each with the files that make it one.
std::set<std::string> codeFolders() {
  std::set<std::string> folders;
  for (const auto& file : sourceTreeFiles())
    if (isCode(file)) folders.insert(layerOf(file));
  return folders;
}

TEST(Layers, TableIsWellFormed) {
  const LayerTable table = loadLayerTable();
  for (const std::string& error : table.errors) ADD_FAILURE() << error;
  for (const auto& [name, row] : table.rows) {
    for (const std::string& below : row.standsOn) {
      EXPECT_TRUE(table.rows.contains(below))
          << "docs/architecture.md:" << row.line << ": `" << name << "` stands on `" << below << "`, which has no row";
      EXPECT_FALSE(allowedIncludes(table, below).contains(name))
          << "docs/architecture.md:" << row.line << ": cycle: `" << name << "` stands on `" << below
          << "`, which reaches `" << name << "` again";
    }
  }
}

TEST(Layers, EverySrcFolderHasARowAndAReadme) {
  const LayerTable table = loadLayerTable();
  const std::set<std::string> folders = codeFolders();
  for (const std::string& folder : folders) {
    EXPECT_TRUE(table.rows.contains(folder))
        << "src/" << folder << " holds code but has no row in docs/architecture.md (Layer table)";
    EXPECT_TRUE(std::filesystem::exists(sourceDir() + "/src/" + folder + "/README.md"))
        << "src/" << folder << " has no README.md (what it owns, what it may include, its docs and tests)";
  }
  for (const auto& [name, row] : table.rows) {
    if (row.planned)
      EXPECT_FALSE(folders.contains(name))
          << "docs/architecture.md:" << row.line << ": src/" << name << " exists: drop `[planned]` from its row";
    else
      EXPECT_TRUE(folders.contains(name))
          << "docs/architecture.md:" << row.line << ": no code in src/" << name << ": remove the row or mark it `[planned]`";
  }
}

TEST(Layers, EveryIncludeGoesDownward) {
  const LayerTable table = loadLayerTable();
  std::set<std::pair<std::string, std::string>> exceptionsSeen;
  static const std::regex kInclude(R"(^\s*#\s*include\s*"([^"]+)\")");
  for (const auto& file : sourceTreeFiles()) {
    if (!isCode(file)) continue;
    const std::string layer = layerOf(file), path = repoPath(file);
    const std::set<std::string> allowed = allowedIncludes(table, layer);
    std::istringstream lines(test::readFile(file));
    std::string line;
    std::smatch include;
    for (int number = 1; std::getline(lines, line); ++number) {
      if (!std::regex_search(line, include, kInclude)) continue;
      const std::string header = include[1], where = path + ":" + std::to_string(number) + ": ";
      const auto slash = header.rfind('/');
      if (slash == std::string::npos) {
        ADD_FAILURE() << where << "include \"" << header << "\" is not path-qualified (\"" << layer << "/" << header << "\")";
        continue;
      }
      const std::string target = header.substr(0, slash);
      if (target == layer || allowed.contains(target)) continue;
      const bool excepted = std::ranges::any_of(
          table.exceptions, [&](const LayerException& e) { return e.file == path && e.header == header; });
      if (excepted) {
        exceptionsSeen.emplace(path, header);
        continue;
      }
      ADD_FAILURE() << where << layer << " may not include " << header << " (allowed: " << joined(allowed) << ")";
    }
  }
  for (const LayerException& e : table.exceptions)
    EXPECT_TRUE(exceptionsSeen.contains({e.file, e.header}))
        << "docs/architecture.md:" << e.line << ": " << e.file << " no longer includes " << e.header
        << " against the table: delete this known exception";
}

// The checks themselves, on a table small enough to know the answers.
TEST(Layers, TableReaderFollowsRowsTransitively) {
  const LayerTable table = parseLayerTable(
      "```layers\n"
      "low:\n"
      "mid: low   # comment\n"
      "top: mid, side [planned]\n"
      "side:\n"
      "```\n"
      "```layer-exceptions\n"
      "src/low/a.hpp: top/b.hpp\n"
      "```\n");
  EXPECT_TRUE(table.errors.empty());
  EXPECT_EQ(allowedIncludes(table, "top"), (std::set<std::string>{"low", "mid", "side"}));
  EXPECT_TRUE(allowedIncludes(table, "low").empty());
  EXPECT_TRUE(table.rows.at("top").planned);
  ASSERT_EQ(table.exceptions.size(), 1u);
  EXPECT_EQ(table.exceptions[0].header, "top/b.hpp");
  EXPECT_EQ(parseLayerTable("```layers\nlow:\nno colon\n```\n").errors.size(), 1u);
}

}  // namespace
}  // namespace virtcom::layers
