// The line reader of .ad files; the structural checks are in check.cpp.
#include "lang/ad/reader.hpp"

#include <cctype>
#include <map>
#include <string>

#include "core/iec_literal.hpp"
#include "lang/ad/diagnostic_codes.hpp"

namespace virtcom::ad {

namespace {

struct Word {
  std::string_view text;
  SourceLocation loc;
};

bool isIdentifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

bool isDigits(std::string_view s) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

// %IX3.5, %QX0.0, %MX10.7 (any case): one BOOL of the process image; the area letter is s[1].
bool isBitAddress(std::string_view s) {
  if (s.size() < 6 || s[0] != '%' || std::toupper(static_cast<unsigned char>(s[2])) != 'X') return false;
  char area = static_cast<char>(std::toupper(static_cast<unsigned char>(s[1])));
  size_t dot = s.find('.', 3);
  return (area == 'I' || area == 'Q' || area == 'M') && dot != std::string_view::npos &&
         isDigits(s.substr(3, dot - 3)) && s.size() == dot + 2 && s[dot + 1] >= '0' && s[dot + 1] <= '7';
}

// An activity's binding: an identifier, a dotted path (GVL.x) or a bit address (%IX0.0).
bool isVariable(std::string_view s) {
  if (!s.empty() && s[0] == '%') return isBitAddress(s);
  size_t start = 0;
  for (size_t dot = s.find('.'); ; dot = s.find('.', start)) {
    if (!isIdentifier(s.substr(start, dot - start))) return false;
    if (dot == std::string_view::npos) return true;
    start = dot + 1;
  }
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

class Reader {
 public:
  Reader(uint32_t fileId, Diagnostics& diags) : fileId_(fileId), diags_(diags) {}

  Program read(std::string_view text) {
    uint32_t lineNo = 0;
    size_t pos = 0;
    while (pos <= text.size()) {
      size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      readLine(text.substr(pos, end - pos), ++lineNo);
      pos = end + 1;
    }
    if (diagram_) {
      diags_.error(diag::A001, diagram_->loc, "diagram '" + diagram_->name + "' has no end_diagram");
      closeDiagram();
    }
    if (!sawProgram_) diags_.error(diag::A001, {fileId_, 1, 1}, "a diagram file starts with `program NAME`");
    return std::move(program_);
  }

 private:
  struct PendingArc {
    Word from, arrow, to;
  };

  std::vector<Word> split(std::string_view line, uint32_t lineNo) {
    std::vector<Word> words;
    size_t comment = line.find("//");
    if (comment != std::string_view::npos) line = line.substr(0, comment);
    size_t i = 0;
    while (i < line.size()) {
      if (std::isspace(static_cast<unsigned char>(line[i]))) { ++i; continue; }
      size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      words.push_back({line.substr(start, i - start), {fileId_, lineNo, static_cast<uint32_t>(start + 1)}});
    }
    return words;
  }

  void readLine(std::string_view line, uint32_t lineNo) {
    std::vector<Word> w = split(line, lineNo);
    if (w.empty()) return;
    if (w.size() == 3 && arcKindFromArrow(w[1].text)) return readArc(w);
    std::string keyword = lower(w[0].text);
    if (keyword == "program") return readProgramLine(w);
    if (keyword == "port") return readPort(w);
    if (keyword == "diagram") return openDiagram(w);
    if (keyword == "end_diagram") return endDiagram(w);
    if (auto kind = nodeKindFromKeyword(keyword)) return readNode(*kind, w);
    diags_.error(diag::A002, w[0].loc, "unknown keyword '" + std::string(w[0].text) +
                                           "' (expected program, port, diagram, an element or an arc `A -> B`)");
  }

  bool expectCount(const std::vector<Word>& w, size_t min, size_t max, std::string_view form) {
    if (w.size() >= min && w.size() <= max) return true;
    diags_.error(diag::A001, w[0].loc, "expected `" + std::string(form) + "`");
    return false;
  }

  bool expectIdentifier(const Word& word, std::string_view what) {
    if (isIdentifier(word.text)) return true;
    diags_.error(diag::A001, word.loc, std::string(what) + " '" + std::string(word.text) + "' is not a name");
    return false;
  }

  // Reports A003 if `name` was already declared in the file: ports, diagrams, timers, counters
  // and bars share one name space (the last three become variables next to the ports).
  bool declare(const Word& name, std::string_view what) {
    auto [it, fresh] = names_.emplace(lower(name.text), name.loc);
    if (fresh) return true;
    diags_.error(diag::A003, name.loc, std::string(what) + " '" + std::string(name.text) + "' is already declared at line " +
                                           std::to_string(it->second.line));
    return false;
  }

  void readProgramLine(const std::vector<Word>& w) {
    if (!expectCount(w, 2, 2, "program NAME") || !expectIdentifier(w[1], "program")) return;
    if (sawProgram_) {
      diags_.error(diag::A003, w[0].loc, "a file holds one program");
      return;
    }
    sawProgram_ = true;
    program_.name = w[1].text;
    program_.loc = w[0].loc;
  }

  void readPort(const std::vector<Word>& w) {
    if (!expectCount(w, 3, 4, "port NAME I|O|M [%ADDRESS]") || !expectIdentifier(w[1], "port")) return;
    Port port{std::string(w[1].text), PortKind::Memory, w.size() == 4 ? std::string(w[3].text) : "", w[0].loc};
    std::string kind = lower(w[2].text);
    const char* area = kind == "i" ? "%I" : kind == "o" ? "%Q" : kind == "m" ? "%M" : nullptr;
    if (!area) {
      diags_.error(diag::A013, w[2].loc, "port kind '" + std::string(w[2].text) + "' is not I, O or M");
      return;
    }
    port.kind = kind == "i" ? PortKind::Input : kind == "o" ? PortKind::Output : PortKind::Memory;
    if (!port.address.empty() && (!isBitAddress(port.address) || lower(port.address.substr(0, 2)) != lower(area))) {
      diags_.error(diag::A013, w[3].loc, "a BOOL port of kind " + std::string(w[2].text) + " is located at " + area +
                                             "X<byte>.<bit>, not '" + port.address + "'");
      return;
    }
    if (diagram_) diags_.error(diag::A001, w[0].loc, "ports are declared before the first diagram");
    if (declare(w[1], "port")) program_.ports.push_back(std::move(port));
  }

  void openDiagram(const std::vector<Word>& w) {
    if (diagram_) {
      diags_.error(diag::A001, w[0].loc, "diagram '" + diagram_->name + "' is not closed by end_diagram");
      closeDiagram();
    }
    if (!expectCount(w, 2, 2, "diagram NAME") || !expectIdentifier(w[1], "diagram")) return;
    declare(w[1], "diagram");  // a duplicate is still read, so its own mistakes are reported too
    program_.diagrams.emplace_back();
    diagram_ = &program_.diagrams.back();
    diagram_->name = w[1].text;
    diagram_->loc = w[0].loc;
  }

  void endDiagram(const std::vector<Word>& w) {
    if (!diagram_) {
      diags_.error(diag::A001, w[0].loc, "end_diagram without a diagram");
      return;
    }
    expectCount(w, 1, 1, "end_diagram");
    closeDiagram();
  }

  void readNode(NodeKind kind, const std::vector<Word>& w) {
    if (!diagram_) {
      diags_.error(diag::A001, w[0].loc, "elements are declared inside `diagram NAME` ... `end_diagram`");
      return;
    }
    Node node;
    node.kind = kind;
    node.loc = w[0].loc;
    if (!readNodeTail(node, w) || !expectIdentifier(w[1], "element id")) return;
    node.id = w[1].text;
    if (auto it = ids_.find(lower(node.id)); it != ids_.end()) {
      diags_.error(diag::A003, w[1].loc, "element '" + node.id + "' is already declared at line " +
                                             std::to_string(diagram_->nodes[it->second].loc.line));
      return;
    }
    // Timers, counters and (grouped) joins become variables of the program, next to the ports.
    // A clash is reported, but the element is kept so its arcs do not add follow-up errors.
    if (isBlock(kind) || isBar(kind)) declare(w[1], "element");
    ids_.emplace(lower(node.id), diagram_->nodes.size());
    diagram_->nodes.push_back(std::move(node));
  }

  // What follows the id: an activity's variable, a timer's or counter's type and preset.
  bool readNodeTail(Node& node, const std::vector<Word>& w) {
    switch (node.kind) {
      case NodeKind::Activity:
        if (!expectCount(w, 2, 3, "activity ID [VARIABLE]")) return false;
        node.variable = w.back().text;
        if (isVariable(node.variable)) return true;
        diags_.error(diag::A001, w.back().loc, "'" + node.variable + "' is neither a name nor a bit address such as %IX0.0");
        return false;
      case NodeKind::Timer:
        return expectCount(w, 4, 4, "timer ID TON|TOF|TP T#PRESET") && readBlock(node, w, true);
      case NodeKind::Counter:
        return expectCount(w, 4, 4, "counter ID CTU|CTD PRESET") && readBlock(node, w, false);
      default:
        return expectCount(w, 2, 2, std::string(nodeKeyword(node.kind)) + " ID");
    }
  }

  bool readBlock(Node& node, const std::vector<Word>& w, bool timer) {
    auto type = blockTypeFromName(w[2].text);
    if (!type || isTimerBlock(*type) != timer) {
      std::string message = "'";  // built by parts: GCC 12 warns (-Wrestrict) on "'" + std::string(...) + ... here
      message += w[2].text;
      message += "' is not a ";
      message += timer ? "timer type (TON, TOF, TP)" : "counter type (CTU, CTD)";
      diags_.error(diag::A012, w[2].loc, std::move(message));
      return false;
    }
    node.block = *type;
    return timer ? readTimePreset(node, w[3]) : readCountPreset(node, w[3]);
  }

  bool readTimePreset(Node& node, const Word& word) {
    int64_t ms = 0;
    std::string_view text = word.text;
    bool prefixed = text.size() > 2 && lower(text.substr(0, 2)) == "t#";
    if (!prefixed || !parseTimeOrDateText(text, LiteralFamily::Time, ms) || ms < 0) {
      diags_.error(diag::A012, word.loc, "timer preset '" + std::string(text) + "' is not a duration such as T#5s");
      return false;
    }
    node.presetNs = ms * 1'000'000;
    return true;
  }

  bool readCountPreset(Node& node, const Word& word) {
    uint64_t count = 0;
    if (!parseDecimal(word.text, count) || count > 32767) {
      diags_.error(diag::A012, word.loc, "counter preset '" + std::string(word.text) + "' is not a count 0..32767");
      return false;
    }
    node.presetCount = count;
    return true;
  }

  void readArc(const std::vector<Word>& w) {
    if (!diagram_) {
      diags_.error(diag::A001, w[0].loc, "arcs are written inside `diagram NAME` ... `end_diagram`");
      return;
    }
    arcs_.push_back({w[0], w[1], w[2]});
  }

  // Resolves the diagram's arcs (written anywhere in it) to its elements.
  void closeDiagram() {
    for (const PendingArc& p : arcs_) {
      auto from = resolve(p.from), to = resolve(p.to);
      if (from && to) diagram_->arcs.push_back({*arcKindFromArrow(p.arrow.text), *from, *to, p.arrow.loc});
    }
    arcs_.clear();
    ids_.clear();
    diagram_ = nullptr;
  }

  std::optional<size_t> resolve(const Word& word) {
    auto it = ids_.find(lower(word.text));
    if (it != ids_.end()) return it->second;
    diags_.error(diag::A004, word.loc, "the arc names '" + std::string(word.text) + "', which diagram '" + diagram_->name +
                                           "' does not declare");
    return std::nullopt;
  }

  uint32_t fileId_;
  Diagnostics& diags_;
  Program program_;
  bool sawProgram_ = false;
  Diagram* diagram_ = nullptr;  // the open diagram (program_.diagrams is not resized while open)
  std::vector<PendingArc> arcs_;
  std::map<std::string, size_t> ids_;              // element id (lower case) -> node index
  std::map<std::string, SourceLocation> names_;    // every declared name in the file
};

}  // namespace

Program readProgram(uint32_t fileId, std::string_view text, Diagnostics& diags) {
  size_t errorsBefore = diags.errorCount();
  Program program = Reader(fileId, diags).read(text);
  if (diags.errorCount() == errorsBefore) checkProgram(program, diags);
  return program;
}

bool isDiagramPath(std::string_view path) {
  return path.size() >= 3 && path[path.size() - 3] == '.' && lower(path.substr(path.size() - 2)) == "ad";
}

}  // namespace virtcom::ad
