#pragma once
// Test-only: a tiny YAML subset (block maps, block lists of scalars, flow [..] and {..},
// "quoted" scalars, # comment lines) turned into ConfigNodes with exact line:col positions, so
// device tests can write cell-file snippets and check where diagnostics point.
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include "core/config_node.hpp"

namespace virtcom::plant::test {

class MiniYaml {
 public:
  static ConfigNode parse(const std::string& text, uint32_t fileId = 0) {
    MiniYaml y;
    y.fileId_ = fileId;
    std::istringstream in(text);
    std::string line;
    uint32_t n = 0;
    while (std::getline(in, line)) {
      ++n;
      size_t ind = line.find_first_not_of(' ');
      if (ind == std::string::npos || line[ind] == '#') continue;
      y.lines_.push_back({n, static_cast<int>(ind), line});
    }
    size_t i = 0;
    if (y.lines_.empty()) return ConfigNode::makeMap({fileId, 1, 1});
    return y.block(i, y.lines_[0].indent);
  }

 private:
  struct Line {
    uint32_t no;
    int indent;
    std::string text;
  };

  SourceLocation at(uint32_t line, size_t col0) const { return {fileId_, line, static_cast<uint32_t>(col0 + 1)}; }

  ConfigNode block(size_t& i, int indent) {
    const Line& first = lines_[i];
    if (first.text.compare(static_cast<size_t>(indent), 2, "- ") == 0) {
      ConfigNode list = ConfigNode::makeList(at(first.no, static_cast<size_t>(indent)));
      while (i < lines_.size() && lines_[i].indent == indent && lines_[i].text.compare(static_cast<size_t>(indent), 2, "- ") == 0) {
        const Line& l = lines_[i++];
        size_t p = static_cast<size_t>(indent) + 2;
        while (p < l.text.size() && l.text[p] == ' ') ++p;
        list.push(value(l, p));
      }
      return list;
    }
    ConfigNode map = ConfigNode::makeMap(at(first.no, static_cast<size_t>(indent)));
    while (i < lines_.size() && lines_[i].indent == indent) {
      const Line& l = lines_[i++];
      size_t colon = keyEnd(l.text, static_cast<size_t>(indent));
      std::string key = unquote(trim(l.text.substr(static_cast<size_t>(indent), colon - static_cast<size_t>(indent))));
      SourceLocation keyLoc = at(l.no, static_cast<size_t>(indent));
      size_t p = colon + 1;
      while (p < l.text.size() && l.text[p] == ' ') ++p;
      if (p >= l.text.size()) {
        if (i < lines_.size() && lines_[i].indent > indent) {
          map.add(key, keyLoc, block(i, lines_[i].indent));
        } else {
          map.add(key, keyLoc, ConfigNode::makeScalar("", at(l.no, p)));
        }
      } else {
        map.add(key, keyLoc, value(l, p));
      }
    }
    return map;
  }

  static size_t keyEnd(const std::string& s, size_t from) {
    bool quoted = false;
    for (size_t k = from; k < s.size(); ++k) {
      if (s[k] == '"') quoted = !quoted;
      if (!quoted && s[k] == ':' && (k + 1 == s.size() || s[k + 1] == ' ')) return k;
    }
    return s.size();
  }

  // A block value: flow collections and quoted scalars, else the rest of the line verbatim
  // (so `at: 100, 250, 0 mm` stays one scalar as in YAML).
  ConfigNode value(const Line& l, size_t p) {
    char c = l.text[p];
    if (c == '[' || c == '{' || c == '"') return flow(l, p);
    return ConfigNode::makeScalar(trim(l.text.substr(p)), at(l.no, p));
  }

  ConfigNode flow(const Line& l, size_t& p) {
    const std::string& s = l.text;
    while (p < s.size() && s[p] == ' ') ++p;
    if (p < s.size() && s[p] == '[') {
      ConfigNode list = ConfigNode::makeList(at(l.no, p));
      ++p;
      while (true) {
        while (p < s.size() && s[p] == ' ') ++p;
        if (p >= s.size() || s[p] == ']') break;
        list.push(flow(l, p));
        while (p < s.size() && s[p] == ' ') ++p;
        if (p < s.size() && s[p] == ',') ++p;
      }
      ++p;
      return list;
    }
    if (p < s.size() && s[p] == '{') {
      ConfigNode map = ConfigNode::makeMap(at(l.no, p));
      ++p;
      while (true) {
        while (p < s.size() && s[p] == ' ') ++p;
        if (p >= s.size() || s[p] == '}') break;
        size_t k0 = p;
        size_t colon = s.find(':', p);
        std::string key = trim(s.substr(k0, colon - k0));
        p = colon + 1;
        map.add(key, at(l.no, k0), flow(l, p));
        while (p < s.size() && s[p] == ' ') ++p;
        if (p < s.size() && s[p] == ',') ++p;
      }
      ++p;
      return map;
    }
    size_t start = p;
    if (p < s.size() && s[p] == '"') {
      size_t end = s.find('"', p + 1);
      p = end + 1;
      return ConfigNode::makeScalar(s.substr(start + 1, end - start - 1), at(l.no, start));
    }
    int depth = 0;
    while (p < s.size()) {
      char c = s[p];
      if (c == '[' || c == '{') ++depth;
      if ((c == ']' || c == '}') && depth-- == 0) break;
      if (c == ',' && depth == 0) break;
      ++p;
    }
    return ConfigNode::makeScalar(trim(s.substr(start, p - start)), at(l.no, start));
  }

  static std::string trim(const std::string& s) {
    size_t b = s.find_first_not_of(' '), e = s.find_last_not_of(' ');
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
  }
  static std::string unquote(const std::string& s) {
    return s.size() >= 2 && s.front() == '"' && s.back() == '"' ? s.substr(1, s.size() - 2) : s;
  }

  uint32_t fileId_ = 0;
  std::vector<Line> lines_;
};

}  // namespace virtcom::plant::test
