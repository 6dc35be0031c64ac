// Keeps docs/diagnostics.md in sync with src/lang/syntax/diagnostic_codes.def: every ST code needs a
// section `### CODE title` (with the title of the .def), saying what triggers it and how to fix
// it, and the page documents no E/W code that does not exist.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/code_titles.hpp"
#include "support/doc_sections.hpp"

namespace virtcom {
namespace {

constexpr CodeTitle kCodes[] = {
#define X(code, title) {#code, title},
#include "lang/syntax/diagnostic_codes.def"
#undef X
};

const char* const kDocPath = VIRTCOM_SOURCE_DIR "/docs/diagnostics.md";

std::map<std::string, test::DocSection> readSections(bool& found) { return test::readDocSections(kDocPath, found); }

bool isStCode(const std::string& code) {
  if (code.size() != 4 || (code[0] != 'E' && code[0] != 'W')) return false;
  for (size_t i = 1; i < code.size(); ++i)
    if (code[i] < '0' || code[i] > '9') return false;
  return true;
}

TEST(DiagnosticsDoc, EveryCodeHasASection) {
  bool found = false;
  auto sections = readSections(found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  std::vector<std::string> missing;
  for (const CodeTitle& c : kCodes)
    if (!sections.count(std::string(c.code))) missing.push_back(std::string(c.code) + " (" + std::string(c.title) + ")");
  std::string list;
  for (const auto& m : missing) list += "\n  " + m;
  EXPECT_TRUE(missing.empty()) << "docs/diagnostics.md has no `### CODE title` section for these codes of "
                                  "src/lang/syntax/diagnostic_codes.def:"
                               << list;
}

TEST(DiagnosticsDoc, SectionTitlesMatchTheCodeTable) {
  bool found = false;
  auto sections = readSections(found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  for (const CodeTitle& c : kCodes) {
    auto it = sections.find(std::string(c.code));
    if (it == sections.end()) continue;  // reported by EveryCodeHasASection
    EXPECT_EQ(it->second.title, c.title) << "the heading of " << c.code << " in docs/diagnostics.md";
  }
}

TEST(DiagnosticsDoc, EverySectionSaysWhatTriggersItAndHowToFixIt) {
  bool found = false;
  auto sections = readSections(found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  for (const CodeTitle& c : kCodes) {
    auto it = sections.find(std::string(c.code));
    if (it == sections.end()) continue;
    EXPECT_NE(it->second.body.find("**Trigger.**"), std::string::npos) << c.code << " has no **Trigger.** paragraph";
    EXPECT_NE(it->second.body.find("**Fix.**"), std::string::npos) << c.code << " has no **Fix.** paragraph";
  }
}

TEST(DiagnosticsDoc, DocumentsNoUnknownStCode) {
  bool found = false;
  auto sections = readSections(found);
  ASSERT_TRUE(found) << "cannot read " << kDocPath;
  for (const auto& [code, section] : sections) {
    if (!isStCode(code)) continue;  // cell-file codes (C0xx) live elsewhere
    bool known = false;
    for (const CodeTitle& c : kCodes) known = known || c.code == code;
    EXPECT_TRUE(known) << "docs/diagnostics.md documents " << code
                       << ", which is not in src/lang/syntax/diagnostic_codes.def";
  }
}

}  // namespace
}  // namespace virtcom
