// The AD-XML reader (reader.hpp): each element becomes the words of the matching .ad line, with
// the locations of its attributes, and goes through the same builder as the text form.
#include <pugixml.hpp>

#include <string>
#include <vector>

#include "lang/ad/builder.hpp"
#include "lang/ad/diagnostic_codes.hpp"
#include "lang/ad/reader.hpp"
#include "lang/xml/xml_file.hpp"

namespace virtcom::ad {

namespace {

using detail::Word;

// The attributes of an element, in the order of the words of its .ad line; `optional` ones may
// be left out (a port's address, an activity's variable, an arc's kind).
struct Attribute {
  const char* name;
  bool optional = false;
};

// "<timer>": built by appending, as GCC 12 warns (-Wrestrict) on "<" + std::string(...).
std::string tagOf(pugi::xml_node node) {
  std::string tag = "<";
  tag += node.name();
  tag += '>';
  return tag;
}

class XmlReader {
 public:
  XmlReader(const xml::XmlFile& file, Diagnostics& diags) : file_(file), diags_(diags), builder_(file.fileId(), diags) {}

  Program read() {
    pugi::xml_node root = file_.root();
    if (xml::localName(root) != "program") {
      diags_.error(diag::A014, file_.at(root), "the root element is " + tagOf(root) + "; an AD-XML file is one <program name=\"...\">");
      return {};
    }
    if (auto w = words(root, {{"name"}})) builder_.program(*w);
    for (pugi::xml_node child : elements(root)) {
      std::string_view name = xml::localName(child);
      if (name == "port") {
        if (auto w = words(child, {{"name"}, {"kind"}, {"address", true}})) builder_.port(*w);
      } else if (name == "diagram") {
        readDiagram(child);
      } else {
        unknownElement(child, "<port> or <diagram>");
      }
    }
    return builder_.finish();
  }

 private:
  void readDiagram(pugi::xml_node diagram) {
    auto w = words(diagram, {{"name"}});
    if (!w) return;
    builder_.openDiagram(*w);
    for (pugi::xml_node child : elements(diagram)) {
      std::string_view name = xml::localName(child);
      if (name == "arc") {
        readArc(child);
      } else if (auto kind = nodeKindFromKeyword(name)) {
        if (auto nodeWords = words(child, nodeAttributes(*kind))) builder_.node(*kind, *nodeWords);
      } else {
        unknownElement(child, "an element (<activity>, <timer>, <or-join>, ...) or an <arc>");
      }
    }
    builder_.endDiagram({{"end_diagram", file_.at(diagram)}});
  }

  static std::vector<Attribute> nodeAttributes(NodeKind kind) {
    switch (kind) {
      case NodeKind::Activity: return {{"id"}, {"variable", true}};
      case NodeKind::Timer: case NodeKind::Counter: return {{"id"}, {"type"}, {"preset"}};
      case NodeKind::Block: return {{"id"}, {"type"}, {"input", true}, {"output", true}};
      default: return {{"id"}};
    }
  }

  void readArc(pugi::xml_node arc) {
    auto w = words(arc, {{"from"}, {"to"}, {"kind", true}});
    if (!w) return;
    Word kindWord = w->size() == 4 ? (*w)[3] : (*w)[0];
    std::optional<ArcKind> kind = w->size() == 4 ? arcKindFromTableName(kindWord.text) : ArcKind::Normal;
    if (!kind) {
      diags_.error(diag::A001, kindWord.loc, "arc kind '" + std::string(kindWord.text) + "' is not normal, NOT-IN or NOT-OUT");
      return;
    }
    builder_.arc((*w)[1], *kind, kindWord, (*w)[2]);
  }

  // The element's keyword (its name, at its '<') and its attribute values in the order given;
  // nullopt (reported, A001) if a required attribute is missing or an unknown one is present.
  std::optional<std::vector<Word>> words(pugi::xml_node node, const std::vector<Attribute>& attributes) {
    std::vector<Word> out{{xml::localName(node), file_.at(node)}};
    bool ok = true;
    for (pugi::xml_attribute a : node.attributes()) {
      bool known = false;
      for (const Attribute& expected : attributes) known = known || std::string_view(a.name()) == expected.name;
      if (known) continue;
      diags_.error(diag::A001, file_.at(node, a.name()), tagOf(node) + " has no attribute '" + a.name() + "' (expected " +
                                                              attributeList(attributes) + ")");
      ok = false;
    }
    for (const Attribute& expected : attributes) {
      pugi::xml_attribute a = node.attribute(expected.name);
      if (a) {
        out.push_back({a.value(), file_.at(node, expected.name)});
      } else if (!expected.optional) {
        diags_.error(diag::A001, file_.at(node), tagOf(node) + " needs the attribute '" + expected.name + "'");
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    return out;
  }

  static std::string attributeList(const std::vector<Attribute>& attributes) {
    std::string out;
    for (const Attribute& a : attributes) out += std::string(out.empty() ? "" : ", ") + a.name;
    return out;
  }

  // The child elements; non-blank text between them is a mistake (reported, A001).
  std::vector<pugi::xml_node> elements(pugi::xml_node parent) {
    std::vector<pugi::xml_node> out;
    for (pugi::xml_node c = parent.first_child(); c; c = c.next_sibling()) {
      if (c.type() == pugi::node_element) out.push_back(c);
      else if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata)
        diags_.error(diag::A001, file_.at(c), "text inside " + tagOf(parent) + ": only elements are expected");
    }
    return out;
  }

  void unknownElement(pugi::xml_node node, std::string_view expected) {
    diags_.error(diag::A002, file_.at(node), "unknown element " + tagOf(node) + " (expected " + std::string(expected) + ")");
  }

  const xml::XmlFile& file_;
  Diagnostics& diags_;
  detail::ProgramBuilder builder_;
};

}  // namespace

Program readXmlProgram(uint32_t fileId, std::string_view text, Diagnostics& diags) {
  size_t errorsBefore = diags.errorCount();
  xml::XmlFile file(fileId, text, diags, diag::A014);
  if (!file.ok()) return {};
  Program program = XmlReader(file, diags).read();
  if (diags.errorCount() == errorsBefore) checkProgram(program, diags);
  return program;
}

bool isXmlDiagramPath(std::string_view path) {
  return path.size() >= 6 && detail::lowerAscii(path.substr(path.size() - 6)) == ".adxml";
}

Program readProgramFile(uint32_t fileId, std::string_view path, std::string_view text, Diagnostics& diags) {
  return isXmlDiagramPath(path) ? readXmlProgram(fileId, text, diags) : readProgram(fileId, text, diags);
}

}  // namespace virtcom::ad
