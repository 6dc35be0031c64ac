#pragma once
// Checks shared by the tests of report/'s HTML pages (the run report, the sweep page).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace virtcom::report {

// A tiny well-formedness checker: every non-void tag is closed in order, attribute quotes
// balance, <style>/<script> bodies are skipped. Returns "" when fine, else what went wrong.
inline std::string checkBalanced(const std::string& html) {
  static const std::vector<std::string> kVoid = {"meta", "link", "br", "hr", "img", "input"};
  std::vector<std::string> stack;
  size_t i = 0;
  while ((i = html.find('<', i)) != std::string::npos) {
    if (html.compare(i, 4, "<!--") == 0) {
      i = html.find("-->", i);
      if (i == std::string::npos) return "unterminated comment";
      continue;
    }
    if (html.compare(i, 2, "<!") == 0) {
      i = html.find('>', i);
      continue;
    }
    // Find the end of the tag, honouring quoted attribute values.
    size_t j = i + 1;
    char quote = 0;
    for (; j < html.size(); ++j) {
      if (quote) {
        if (html[j] == quote) quote = 0;
      } else if (html[j] == '"' || html[j] == '\'') {
        quote = html[j];
      } else if (html[j] == '<') {
        return "'<' inside a tag at offset " + std::to_string(j);
      } else if (html[j] == '>') {
        break;
      }
    }
    if (j >= html.size()) return "unterminated tag at offset " + std::to_string(i);
    std::string tag = html.substr(i + 1, j - i - 1);
    bool closing = tag.starts_with('/');
    bool selfClosing = tag.ends_with('/');
    std::string name;
    for (size_t k = closing ? 1 : 0; k < tag.size() && (std::isalnum(static_cast<unsigned char>(tag[k])) || tag[k] == '-'); ++k)
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(tag[k])));
    if (name.empty()) return "bad tag <" + tag + ">";
    i = j + 1;
    if (closing) {
      if (stack.empty() || stack.back() != name)
        return "</" + name + "> closes <" + (stack.empty() ? std::string("nothing") : stack.back()) + ">";
      stack.pop_back();
    } else if (!selfClosing && std::find(kVoid.begin(), kVoid.end(), name) == kVoid.end()) {
      if (name == "style" || name == "script") {
        size_t end = html.find("</" + name + ">", i);
        if (end == std::string::npos) return "unterminated <" + name + ">";
        i = end + name.size() + 3;
        continue;
      }
      stack.push_back(name);
    }
  }
  return stack.empty() ? "" : "unclosed <" + stack.back() + ">";
}

}  // namespace virtcom::report
