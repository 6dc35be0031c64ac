// The checks and model building shared by the .ad text reader and the AD-XML reader (builder.hpp).
#include "lang/ad/builder.hpp"

#include <cctype>

#include "core/iec_literal.hpp"
#include "lang/ad/diagnostic_codes.hpp"

namespace virtcom::ad::detail {

namespace {

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

}  // namespace

std::string lowerAscii(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool ProgramBuilder::expectCount(const std::vector<Word>& w, size_t min, size_t max, std::string_view form) {
  if (w.size() >= min && w.size() <= max) return true;
  diags_.error(diag::A001, w[0].loc, "expected `" + std::string(form) + "`");
  return false;
}

bool ProgramBuilder::expectIdentifier(const Word& word, std::string_view what) {
  if (isIdentifier(word.text)) return true;
  diags_.error(diag::A001, word.loc, std::string(what) + " '" + std::string(word.text) + "' is not a name");
  return false;
}

// Reports A003 if `name` was already declared in the file: ports, diagrams, timers, counters
// and bars share one name space (the last three become variables next to the ports).
bool ProgramBuilder::declare(const Word& name, std::string_view what) {
  auto [it, fresh] = names_.emplace(lowerAscii(name.text), name.loc);
  if (fresh) return true;
  diags_.error(diag::A003, name.loc, std::string(what) + " '" + std::string(name.text) + "' is already declared at line " +
                                         std::to_string(it->second.line));
  return false;
}

void ProgramBuilder::program(const std::vector<Word>& w) {
  if (!expectCount(w, 2, 2, "program NAME") || !expectIdentifier(w[1], "program")) return;
  if (sawProgram_) {
    diags_.error(diag::A003, w[0].loc, "a file holds one program");
    return;
  }
  sawProgram_ = true;
  program_.name = w[1].text;
  program_.loc = w[0].loc;
}

void ProgramBuilder::port(const std::vector<Word>& w) {
  if (!expectCount(w, 3, 4, "port NAME I|O|M [%ADDRESS]") || !expectIdentifier(w[1], "port")) return;
  Port port{std::string(w[1].text), PortKind::Memory, w.size() == 4 ? std::string(w[3].text) : "", w[0].loc};
  std::string kind = lowerAscii(w[2].text);
  const char* area = kind == "i" ? "%I" : kind == "o" ? "%Q" : kind == "m" ? "%M" : nullptr;
  if (!area) {
    diags_.error(diag::A013, w[2].loc, "port kind '" + std::string(w[2].text) + "' is not I, O or M");
    return;
  }
  port.kind = kind == "i" ? PortKind::Input : kind == "o" ? PortKind::Output : PortKind::Memory;
  if (!port.address.empty() && (!isBitAddress(port.address) || lowerAscii(port.address.substr(0, 2)) != lowerAscii(area))) {
    diags_.error(diag::A013, w[3].loc, "a BOOL port of kind " + std::string(w[2].text) + " is located at " + area +
                                           "X<byte>.<bit>, not '" + port.address + "'");
    return;
  }
  if (diagram_) diags_.error(diag::A001, w[0].loc, "ports are declared before the first diagram");
  if (declare(w[1], "port")) program_.ports.push_back(std::move(port));
}

void ProgramBuilder::openDiagram(const std::vector<Word>& w) {
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

void ProgramBuilder::endDiagram(const std::vector<Word>& w) {
  if (!diagram_) {
    diags_.error(diag::A001, w[0].loc, "end_diagram without a diagram");
    return;
  }
  expectCount(w, 1, 1, "end_diagram");
  closeDiagram();
}

void ProgramBuilder::node(NodeKind kind, const std::vector<Word>& w) {
  if (!diagram_) {
    diags_.error(diag::A001, w[0].loc, "elements are declared inside `diagram NAME` ... `end_diagram`");
    return;
  }
  Node node;
  node.kind = kind;
  node.loc = w[0].loc;
  if (!readNodeTail(node, w) || !expectIdentifier(w[1], "element id")) return;
  node.id = w[1].text;
  if (auto it = ids_.find(lowerAscii(node.id)); it != ids_.end()) {
    diags_.error(diag::A003, w[1].loc, "element '" + node.id + "' is already declared at line " +
                                           std::to_string(diagram_->nodes[it->second].loc.line));
    return;
  }
  // Timers, counters and (grouped) joins become variables of the program, next to the ports.
  // A clash is reported, but the element is kept so its arcs do not add follow-up errors.
  if (isBlock(kind) || isBar(kind)) declare(w[1], "element");
  ids_.emplace(lowerAscii(node.id), diagram_->nodes.size());
  diagram_->nodes.push_back(std::move(node));
}

// What follows the id: an activity's variable, a timer's or counter's type and preset, a
// function block's type and pins.
bool ProgramBuilder::readNodeTail(Node& node, const std::vector<Word>& w) {
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
    case NodeKind::Block:
      return readFunctionBlock(node, w);
    default:
      return expectCount(w, 2, 2, std::string(nodeKeyword(node.kind)) + " ID");
  }
}

bool ProgramBuilder::readBlock(Node& node, const std::vector<Word>& w, bool timer) {
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

// `block ID TYPE [INPUT OUTPUT]`: whether TYPE exists and has those BOOLs is the ST checker's.
bool ProgramBuilder::readFunctionBlock(Node& node, const std::vector<Word>& w) {
  if (w.size() != 3 && w.size() != 5) {
    diags_.error(diag::A001, w[0].loc, "expected `block ID TYPE` or `block ID TYPE INPUT OUTPUT`");
    return false;
  }
  for (size_t k = 2; k < w.size(); ++k)
    if (!expectIdentifier(w[k], k == 2 ? "function block type" : "function block pin")) return false;
  node.blockType = w[2].text;
  if (w.size() == 5) {
    node.blockIn = w[3].text;
    node.blockOut = w[4].text;
  }
  return true;
}

bool ProgramBuilder::readTimePreset(Node& node, const Word& word) {
  int64_t ms = 0;
  std::string_view text = word.text;
  bool prefixed = text.size() > 2 && lowerAscii(text.substr(0, 2)) == "t#";
  if (!prefixed || !parseTimeOrDateText(text, LiteralFamily::Time, ms) || ms < 0) {
    diags_.error(diag::A012, word.loc, "timer preset '" + std::string(text) + "' is not a duration such as T#5s");
    return false;
  }
  node.presetNs = ms * 1'000'000;
  return true;
}

bool ProgramBuilder::readCountPreset(Node& node, const Word& word) {
  uint64_t count = 0;
  if (!parseDecimal(word.text, count) || count > 32767) {
    diags_.error(diag::A012, word.loc, "counter preset '" + std::string(word.text) + "' is not a count 0..32767");
    return false;
  }
  node.presetCount = count;
  return true;
}

void ProgramBuilder::arc(const Word& from, ArcKind kind, const Word& kindWord, const Word& to) {
  if (!diagram_) {
    diags_.error(diag::A001, from.loc, "arcs are written inside `diagram NAME` ... `end_diagram`");
    return;
  }
  arcs_.push_back({from, kind, kindWord, to});
}

// Resolves the diagram's arcs (written anywhere in it) to its elements.
void ProgramBuilder::closeDiagram() {
  for (const PendingArc& p : arcs_) {
    auto from = resolve(p.from), to = resolve(p.to);
    if (from && to) diagram_->arcs.push_back({p.kind, *from, *to, p.kindWord.loc});
  }
  arcs_.clear();
  ids_.clear();
  diagram_ = nullptr;
}

std::optional<size_t> ProgramBuilder::resolve(const Word& word) {
  auto it = ids_.find(lowerAscii(word.text));
  if (it != ids_.end()) return it->second;
  diags_.error(diag::A004, word.loc, "the arc names '" + std::string(word.text) + "', which diagram '" + diagram_->name +
                                         "' does not declare");
  return std::nullopt;
}

Program ProgramBuilder::finish() {
  if (diagram_) {
    diags_.error(diag::A001, diagram_->loc, "diagram '" + diagram_->name + "' has no end_diagram");
    closeDiagram();
  }
  if (!sawProgram_) diags_.error(diag::A001, {fileId_, 1, 1}, "a diagram file starts with `program NAME`");
  return std::move(program_);
}

}  // namespace virtcom::ad::detail
