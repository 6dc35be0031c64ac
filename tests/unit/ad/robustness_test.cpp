// The reader, checks, decomposition and lowering on damaged input: seeded random edits of the
// example must never crash or hang, and every diagnostic must point into the text. (The
// libFuzzer target tests/fuzz/fuzz_ad_reader.cpp does the same without bounds.)
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "ad_fixture.hpp"
#include "lang/ad/decompose.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/tables.hpp"
#include "support/read_file.hpp"

namespace virtcom::ad {
namespace {

// Deletes, duplicates or swaps a line, or overwrites a character with one of the format's own.
std::string mutate(std::string text, std::mt19937& rng) {
  static const std::string kAlphabet = "->| \n%IXQM.AStartopjinsplt#0123456789_/";
  for (int edits = 1 + static_cast<int>(rng() % 4); edits > 0 && !text.empty(); --edits) {
    size_t at = rng() % text.size();
    size_t lineStart = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
    size_t lineEnd = std::min(text.find('\n', at), text.size());
    std::string line = text.substr(lineStart, lineEnd - lineStart);
    switch (rng() % 4) {
      case 0: text.erase(lineStart, lineEnd - lineStart); break;
      case 1: text.insert(lineStart, line + "\n"); break;
      case 2: text[at] = kAlphabet[rng() % kAlphabet.size()]; break;
      default: text.insert(rng() % text.size(), line + "\n"); break;
    }
  }
  return text;
}

TEST(AdRobustness, DamagedDiagramsGiveDiagnosticsOrRunnableCode) {
  const std::string original = virtcom::test::readFile(VIRTCOM_SOURCE_DIR "/examples/activity/tank.ad");
  ASSERT_FALSE(original.empty());
  std::mt19937 rng(14);
  int clean = 0;
  for (int round = 0; round < 1500; ++round) {
    std::string text = mutate(original, rng);
    Diagnostics diags;
    Program program = readProgram(0, text, diags);
    uint32_t lines = static_cast<uint32_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    for (const Diagnostic& d : diags.all()) ASSERT_LE(d.loc.line, lines) << d.message;
    if (diags.hasErrors()) continue;
    ++clean;
    std::vector<DiagramTables> tables;
    for (const Diagram& d : program.diagrams) tables.push_back(decompose(d));
    EXPECT_EQ(formatTables(program, tables, TableFormat::Text).empty(), program.diagrams.empty());
    Diagnostics compileDiags;
    (void)test::compileText("tank.ad", text, compileDiags);
  }
  EXPECT_GT(clean, 20) << "the edits should leave some diagrams valid";
}

}  // namespace
}  // namespace virtcom::ad
