#include "lang/plcopen/twincat_file.hpp"

#include <string>
#include <vector>

#include "core/ascii.hpp"
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/st/parse/lexer.hpp"
#include "lang/st/parse/parser.hpp"
#include "lang/xml/xml_file.hpp"

namespace virtcom::plcopen {

// The XML helpers the reader walks the file with (lang/xml).
using xml::child;
using xml::children;
using xml::firstElement;
using xml::firstText;
using xml::localName;
using xml::XmlFile;

namespace {

// The ST text of a TwinCAT file, laid out so that every character of every CDATA section stays
// at its byte offset in the XML file (the markup in between becomes spaces, its line breaks
// stay), and the keywords TwinCAT keeps in the markup (END_METHOD, GET, ACTION A:, ...) are
// written into the blanked markup between the sections, in document order. Locations of the
// ST parser then are locations in the XML file, without a position map.
class StLayout {
 public:
  StLayout(std::string_view xml, const XmlFile& file, Diagnostics& diags) : xml_(xml), file_(file), diags_(diags) {}

  // The ST text of a CDATA section (or of a plain text node without entity references).
  void section(pugi::xml_node owner) {
    pugi::xml_node text = owner.first_child();
    while (text && text.type() != pugi::node_cdata && text.type() != pugi::node_pcdata) text = text.next_sibling();
    if (!text) return;  // an empty <ST/> or <Declaration/>
    auto begin = static_cast<size_t>(text.offset_debug());
    size_t end = text.type() == pugi::node_cdata ? xml_.find("]]>", begin) : xml_.find('<', begin);
    if (end == std::string_view::npos) end = xml_.size();
    if (text.type() == pugi::node_pcdata && xml_.substr(begin, end - begin).find('&') != std::string_view::npos) {
      diags_.error(diag::X004, file_.at(text), "ST text with XML entity references; TwinCAT writes ST as CDATA");
      return;
    }
    items_.push_back({begin, end, {}});
  }

  // A keyword placed after everything before it and before the next section.
  void keyword(std::string words) { items_.push_back({0, 0, std::move(words)}); }

  std::string text() const {
    std::string out(xml_.size(), ' ');
    for (size_t i = 0; i < xml_.size(); ++i)
      if (xml_[i] == '\n') out[i] = '\n';
    size_t cursor = 0;
    for (size_t i = 0; i < items_.size(); ++i) {
      const Item& item = items_[i];
      if (item.words.empty()) {
        out.replace(item.begin, item.end - item.begin, xml_.substr(item.begin, item.end - item.begin));
        cursor = item.end;
        continue;
      }
      size_t limit = xml_.size();
      for (size_t j = i + 1; j < items_.size(); ++j)
        if (items_[j].words.empty()) {
          limit = items_[j].begin;
          break;
        }
      cursor = place(out, item.words, cursor, limit);
    }
    return out;
  }

 private:
  struct Item {
    size_t begin, end;  // a section's bytes in the XML
    std::string words;  // or a keyword
  };

  // Writes `words` into a run of spaces on one line in [from, limit) with a blank on either
  // side; returns where it ends. Every TwinCAT element between two sections is a tag with a
  // name, so there is room; a hand-written file without any gets the words appended at the
  // end, which the parser reports as misplaced.
  static size_t place(std::string& out, const std::string& words, size_t from, size_t limit) {
    size_t run = 0;
    for (size_t p = from; p < limit; ++p) {
      run = out[p] == ' ' ? run + 1 : 0;
      if (run == words.size() + 2) {
        size_t start = p - words.size();
        out.replace(start, words.size(), words);
        return start + words.size();
      }
    }
    out += ' ' + words + ' ';
    return out.size();
  }

  std::string_view xml_;
  const XmlFile& file_;
  Diagnostics& diags_;
  std::vector<Item> items_;
};

// The keyword a declaration starts with (after comments and pragmas), as the ST lexer reads
// it; its diagnostics are dropped here because the ST parser reports them again.
st::Tok firstKeyword(std::string_view declaration) {
  Diagnostics ignored;
  for (const st::Token& t : st::lex(0, declaration, ignored))
    if (t.kind != st::Tok::Pragma) return t.kind;
  return st::Tok::Eof;
}

// `POU 'MAIN'`, `Method 'Reset'`: TwinCAT names elements with a capitalised Name attribute.
std::string named(pugi::xml_node node) {
  std::string out(localName(node));
  if (pugi::xml_attribute name = node.attribute("Name")) out += " '" + std::string(name.value()) + "'";
  return out;
}

std::string sectionText(pugi::xml_node owner) {
  for (pugi::xml_node t = owner.first_child(); t; t = t.next_sibling())
    if (t.type() == pugi::node_cdata || t.type() == pugi::node_pcdata) return t.value();
  return {};
}

class TwinCatReader {
 public:
  TwinCatReader(std::string_view xml, const XmlFile& file, Diagnostics& diags)
      : file_(file), diags_(diags), layout_(xml, file, diags) {}

  std::string read() {
    pugi::xml_node root = file_.root();
    if (localName(root) != "TcPlcObject") {
      diags_.error(diag::X002, file_.at(root), "the root element is <" + std::string(localName(root)) +
                                                   ">; a TwinCAT source file has <TcPlcObject>");
      return {};
    }
    for (pugi::xml_node object = firstElement(root); object; object = object.next_sibling()) {
      if (object.type() != pugi::node_element) continue;
      std::string_view kind = localName(object);
      if (kind == "POU" || kind == "Itf") pou(object);
      else if (kind == "DUT" || kind == "GVL") declaration(object);
      else if (kind == "Task")
        diags_.warning(diag::X101, file_.at(object),
                       named(object) + ": TwinCAT task settings are not read; declare the task in a CONFIGURATION "
                                          "or use --cycle-time (default: one 10 ms task)");
    }
    return layout_.text();
  }

 private:
  bool declaration(pugi::xml_node owner) {
    pugi::xml_node decl = child(owner, "Declaration");
    if (!decl) {
      diags_.error(diag::X003, file_.at(owner), named(owner) + " has no <Declaration>");
      return false;
    }
    layout_.section(decl);
    return true;
  }

  void implementation(pugi::xml_node owner) {
    pugi::xml_node impl = child(owner, "Implementation");
    if (!impl) return;
    pugi::xml_node body = firstElement(impl);
    if (!body) return;
    if (localName(body) == "ST") {
      layout_.section(body);
      return;
    }
    diags_.error(diag::X004, file_.at(body),
                 named(owner) + " is written in " + std::string(localName(body)) +
                     "; only ST bodies of TwinCAT files are read (export graphical POUs as PLCopen XML)");
  }

  void pou(pugi::xml_node object) {
    const char* end = nullptr;
    switch (firstKeyword(sectionText(child(object, "Declaration")))) {
      case st::Tok::KwProgram: end = "END_PROGRAM"; break;
      case st::Tok::KwFunctionBlock: end = "END_FUNCTION_BLOCK"; break;
      case st::Tok::KwFunction: end = "END_FUNCTION"; break;
      case st::Tok::KwInterface: end = "END_INTERFACE"; break;
      default: break;
    }
    if (!end) {
      diags_.error(diag::X003, file_.at(object), named(object) +
                                                     ": the declaration must start with PROGRAM, FUNCTION_BLOCK, "
                                                     "FUNCTION or INTERFACE");
      return;
    }
    if (!declaration(object)) return;
    implementation(object);
    for (pugi::xml_node member = firstElement(object); member; member = member.next_sibling()) {
      std::string_view kind = localName(member);
      if (kind == "Method") method(member);
      else if (kind == "Property") property(member);
      else if (kind == "Action") action(member);
      else if (kind == "Transition")
        diags_.error(diag::X004, file_.at(member), named(member) + ": SFC transitions of TwinCAT files are not read");
    }
    layout_.keyword(end);
  }

  void method(pugi::xml_node member) {
    if (!declaration(member)) return;
    implementation(member);
    layout_.keyword("END_METHOD");
  }

  void property(pugi::xml_node member) {
    if (!declaration(member)) return;
    for (const char* accessor : {"Get", "Set"}) {
      pugi::xml_node part = child(member, accessor);
      if (!part) continue;
      std::string word = accessor == std::string_view("Get") ? "GET" : "SET";
      layout_.keyword(word);
      if (child(part, "Declaration")) layout_.section(child(part, "Declaration"));
      implementation(part);
      layout_.keyword("END_" + word);
    }
    layout_.keyword("END_PROPERTY");
  }

  void action(pugi::xml_node member) {
    std::string name = member.attribute("Name").value();
    if (name.empty()) {
      diags_.error(diag::X003, file_.at(member), "an <Action> has no Name");
      return;
    }
    layout_.keyword("ACTION " + name + ":");
    implementation(member);
    layout_.keyword("END_ACTION");
  }

  const XmlFile& file_;
  Diagnostics& diags_;
  StLayout layout_;
};

}  // namespace

st::CompilationUnit importTwinCatFile(uint32_t fileId, std::string_view text, Diagnostics& diags,
                                      st::NodeId& nextNodeId) {
  XmlFile file(fileId, text, diags, diag::X001);
  if (!file.ok()) return st::CompilationUnit{fileId, {}, {}, {}, {}, {}};
  std::string st = TwinCatReader(text, file, diags).read();
  return st::parseFile(fileId, st, diags, nextNodeId);
}

bool isTwinCatPath(std::string_view path) {
  for (std::string_view ext : {".TcPOU", ".TcIO", ".TcDUT", ".TcGVL", ".TcTTO"})
    if (iendsWithAscii(path, ext)) return true;
  return false;
}

}  // namespace virtcom::plcopen
