// Golden tests of the decomposition: every tests/golden/ad/*.ad file (and the examples under
// examples/activity/) gives its LU and rule tables, compared with the `.tables` file next to it.
// VIRTCOM_UPDATE_GOLDEN=1 rewrites the `.tables` files for review in the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "lang/ad/decompose.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/tables.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;
using virtcom::test::readFile;

namespace virtcom::ad {
namespace {

std::vector<fs::path> goldenDiagrams() {
  std::vector<fs::path> files;
  for (const char* dir : {"tests/golden/ad", "examples/activity"})
    for (const auto& entry : fs::directory_iterator(fs::path(VIRTCOM_SOURCE_DIR) / dir))
      if (entry.path().extension() == ".ad") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

class TablesGolden : public ::testing::TestWithParam<fs::path> {};

TEST_P(TablesGolden, MatchesTheTablesFile) {
  const fs::path& file = GetParam();
  Diagnostics diags;
  Program program = readProgram(0, readFile(file), diags);
  ASSERT_FALSE(diags.hasErrors()) << file << ": " << diags.all().front().message;
  std::vector<DiagramTables> tables;
  for (const Diagram& d : program.diagrams) tables.push_back(decompose(d));
  std::string actual = formatTables(program, tables, TableFormat::Text);
  fs::path expectedFile = fs::path(file).replace_extension(".tables");
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) {
    std::ofstream(expectedFile, std::ios::binary) << actual;
    return;
  }
  ASSERT_TRUE(fs::exists(expectedFile)) << expectedFile << " is missing (VIRTCOM_UPDATE_GOLDEN=1 writes it)";
  EXPECT_EQ(actual, readFile(expectedFile)) << "tables of " << file;
}

INSTANTIATE_TEST_SUITE_P(Ad, TablesGolden, ::testing::ValuesIn(goldenDiagrams()),
                         [](const auto& info) { return info.param.stem().string(); });

}  // namespace
}  // namespace virtcom::ad
