// Keeps docs/diagnostics.md ("Cell files (C0xx)") in sync with src/core/cell_diagnostic_codes.def:
// every cell code has a section `### CODE title` with the title of the .def, saying what triggers
// it and how to fix it; the docs document, and mention anywhere, no C0xx code that does not exist.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <string_view>

#include "core/code_titles.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "support/doc_sections.hpp"
#include "support/read_file.hpp"

namespace virtcom {
namespace {

constexpr CodeTitle kCodes[] = {
#define X(code, title) {#code, title},
#include "core/cell_diagnostic_codes.def"
#undef X
};

const char* const kDocPath = VIRTCOM_SOURCE_DIR "/docs/diagnostics.md";

bool isCellCode(const std::string& code) { return std::regex_match(code, std::regex("C0[0-9][0-9]")); }

bool known(std::string_view code) {
  for (const CodeTitle& c : kCodes)
    if (c.code == code) return true;
  return false;
}

TEST(CellDiagnosticCodes, TitleOfEveryCodeComesFromTheTable) {
  for (const CodeTitle& c : kCodes) EXPECT_EQ(cellDiagnosticTitle(c.code), c.title) << c.code;
  EXPECT_EQ(cellDiagnosticTitle("C999"), "");
  EXPECT_EQ(cellDiagnosticTitle("E001"), "") << "ST codes have their own table";
  EXPECT_EQ(celldiag::C010, "C010");
}

TEST(CellDiagnosticsDoc, EveryCodeHasASectionWithItsTitleTriggerAndFix) {
  bool found = false;
  auto sections = test::readDocSections(kDocPath, found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  for (const CodeTitle& c : kCodes) {
    auto it = sections.find(std::string(c.code));
    if (it == sections.end()) {
      ADD_FAILURE() << "docs/diagnostics.md has no section `### " << c.code << " " << c.title
                    << "` for this code of src/core/cell_diagnostic_codes.def";
      continue;
    }
    EXPECT_EQ(it->second.title, c.title) << "the heading of " << c.code << " in docs/diagnostics.md";
    EXPECT_NE(it->second.body.find("**Trigger.**"), std::string::npos) << c.code << " has no **Trigger.** paragraph";
    EXPECT_NE(it->second.body.find("**Fix.**"), std::string::npos) << c.code << " has no **Fix.** paragraph";
  }
}

TEST(CellDiagnosticsDoc, DocumentsNoUnknownCellCode) {
  bool found = false;
  auto sections = test::readDocSections(kDocPath, found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  for (const auto& [code, section] : sections) {
    if (!isCellCode(code)) continue;  // ST codes: tests/unit/st/docs_sync_test.cpp
    EXPECT_TRUE(known(code)) << "docs/diagnostics.md documents " << code
                             << ", which is not in src/core/cell_diagnostic_codes.def";
  }
}

// The user guide cites codes in examples (`error[C010]: ...`, "is C002"): each must exist.
TEST(CellDiagnosticsDoc, EveryCodeTheGuideMentionsExists) {
  const std::filesystem::path root = VIRTCOM_SOURCE_DIR;
  std::set<std::filesystem::path> pages{root / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md") pages.insert(entry.path());
  const std::regex mention("\\bC0[0-9][0-9]\\b");
  for (const auto& page : pages) {
    const std::string text = test::readFile(page);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), mention); it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(known(it->str())) << page.filename().string() << " mentions " << it->str()
                                    << ", which is not in src/core/cell_diagnostic_codes.def";
  }
}

}  // namespace
}  // namespace virtcom
