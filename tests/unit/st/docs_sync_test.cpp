// Keeps docs/diagnostics.md in sync with src/lang/syntax/diagnostic_codes.def: every ST code needs a
// section `### CODE title` (with the title of the .def), saying what triggers it and how to fix
// it, and the page documents no E/W code that does not exist.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace {

struct CodeTitle {
  std::string_view code;
  std::string_view title;
};

constexpr CodeTitle kCodes[] = {
#define X(code, title) {#code, title},
#include "lang/syntax/diagnostic_codes.def"
#undef X
};

const char* const kDocPath = VIRTCOM_SOURCE_DIR "/docs/diagnostics.md";

struct Section {
  std::string title;  // the rest of the heading line after the code
  std::string body;   // the text up to the next heading
};

// The `### CODE title` sections of docs/diagnostics.md, by code. Empty if the file is missing.
std::map<std::string, Section> readSections(bool& found) {
  std::ifstream in(kDocPath, std::ios::binary);
  found = static_cast<bool>(in);
  std::map<std::string, Section> sections;
  Section* current = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("#", 0) == 0) current = nullptr;  // any heading ends the current section
    if (line.rfind("### ", 0) == 0) {
      std::string rest = line.substr(4);
      size_t space = rest.find(' ');
      std::string code = rest.substr(0, space);
      Section& s = sections[code];
      s.title = space == std::string::npos ? "" : rest.substr(space + 1);
      current = &s;
      continue;
    }
    if (current != nullptr) current->body += line + "\n";
  }
  return sections;
}

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
