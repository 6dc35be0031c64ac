// Keeps docs/diagnostics.md in sync with src/lang/ad/diagnostic_codes.def: every A code has a
// section `### CODE title` with the title of the .def and **Trigger.** / **Fix.** paragraphs,
// and the page documents no A code that does not exist.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <string>
#include <string_view>

#include "core/code_titles.hpp"

namespace {

using virtcom::CodeTitle;

constexpr CodeTitle kCodes[] = {
#define X(code, title) {#code, title},
#include "lang/ad/diagnostic_codes.def"
#undef X
};

struct Section {
  std::string title, body;
};

// The `### A0xx title` sections of docs/diagnostics.md.
std::map<std::string, Section> readSections() {
  std::ifstream in(VIRTCOM_SOURCE_DIR "/docs/diagnostics.md", std::ios::binary);
  std::map<std::string, Section> sections;
  Section* current = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("#", 0) == 0) current = nullptr;
    if (line.rfind("### A", 0) == 0 && line.size() > 5 && std::isdigit(static_cast<unsigned char>(line[5]))) {
      size_t space = line.find(' ', 4);
      current = &sections[line.substr(4, space - 4)];
      current->title = space == std::string::npos ? "" : line.substr(space + 1);
      continue;
    }
    if (current) current->body += line + "\n";
  }
  return sections;
}

TEST(AdDiagnosticsDoc, EveryCodeHasASectionWithItsTitleTriggerAndFix) {
  auto sections = readSections();
  for (const CodeTitle& c : kCodes) {
    auto it = sections.find(std::string(c.code));
    if (it == sections.end()) {
      ADD_FAILURE() << "docs/diagnostics.md has no `### " << c.code << " " << c.title << "` section";
      continue;
    }
    EXPECT_EQ(it->second.title, c.title) << c.code;
    EXPECT_NE(it->second.body.find("**Trigger.**"), std::string::npos) << c.code;
    EXPECT_NE(it->second.body.find("**Fix.**"), std::string::npos) << c.code;
  }
}

TEST(AdDiagnosticsDoc, DocumentsNoUnknownCode) {
  for (const auto& [code, section] : readSections()) {
    bool known = false;
    for (const CodeTitle& c : kCodes) known = known || c.code == code;
    EXPECT_TRUE(known) << "docs/diagnostics.md documents " << code << ", which is not in src/lang/ad/diagnostic_codes.def";
  }
}

}  // namespace
