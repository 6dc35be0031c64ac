// Golden tests of what an activity-diagram file gives: every tests/golden/ad/*.ad file (and the
// examples under examples/activity/) gives its LU and rule tables, compared with the `.tables`
// file next to it, and its drawing as Graphviz DOT text (`virtcom ad render --dot`), compared
// with the `.dot` file next to it. VIRTCOM_UPDATE_GOLDEN=1 rewrites both for review in the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "lang/ad/decompose.hpp"
#include "lang/ad/dot.hpp"
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

class AdGolden : public ::testing::TestWithParam<fs::path> {
 protected:
  Program read() {
    Diagnostics diags;
    Program program = readProgram(0, readFile(GetParam()), diags);
    EXPECT_FALSE(diags.hasErrors()) << GetParam() << ": " << diags.all().front().message;
    return program;
  }
  // Compares `actual` with the file next to the diagram with `extension`, or rewrites it.
  void expectGolden(const std::string& actual, const char* extension) {
    fs::path expectedFile = fs::path(GetParam()).replace_extension(extension);
    if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) {
      std::ofstream(expectedFile, std::ios::binary) << actual;
      return;
    }
    ASSERT_TRUE(fs::exists(expectedFile)) << expectedFile << " is missing (VIRTCOM_UPDATE_GOLDEN=1 writes it)";
    EXPECT_EQ(actual, readFile(expectedFile)) << extension << " of " << GetParam();
  }
};

TEST_P(AdGolden, TablesMatchTheTablesFile) {
  Program program = read();
  std::vector<DiagramTables> tables;
  for (const Diagram& d : program.diagrams) tables.push_back(decompose(d));
  expectGolden(formatTables(program, tables, TableFormat::Text), ".tables");
}

TEST_P(AdGolden, DrawingMatchesTheDotFile) {
  Program program = read();
  std::vector<const Diagram*> all;
  for (const Diagram& d : program.diagrams) all.push_back(&d);
  expectGolden(toDot(program, all), ".dot");
}

INSTANTIATE_TEST_SUITE_P(Ad, AdGolden, ::testing::ValuesIn(goldenDiagrams()),
                         [](const auto& info) { return info.param.stem().string(); });

}  // namespace
}  // namespace virtcom::ad
