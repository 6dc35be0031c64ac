#pragma once
// Test-only: the `### CODE title` sections of a Markdown page (docs/diagnostics.md), for the
// tests that keep a code table (.def) and its documentation in sync.
#include <fstream>
#include <map>
#include <string>

namespace virtcom::test {

struct DocSection {
  std::string title;  // the rest of the heading line after the code
  std::string body;   // the text up to the next heading
};

// The page's `### CODE title` sections by code; `found` says whether the file could be read
// (the map is empty if not). Any heading ends the current section.
inline std::map<std::string, DocSection> readDocSections(const std::string& path, bool& found) {
  std::ifstream in(path, std::ios::binary);
  found = static_cast<bool>(in);
  std::map<std::string, DocSection> sections;
  DocSection* current = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("#", 0) == 0) current = nullptr;
    if (line.rfind("### ", 0) == 0) {
      std::string rest = line.substr(4);
      size_t space = rest.find(' ');
      DocSection& s = sections[rest.substr(0, space)];
      s.title = space == std::string::npos ? "" : rest.substr(space + 1);
      current = &s;
      continue;
    }
    if (current != nullptr) current->body += line + "\n";
  }
  return sections;
}

}  // namespace virtcom::test
