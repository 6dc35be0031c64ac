#include "lang/xml/xml_file.hpp"

#include <algorithm>

namespace virtcom::xml {

XmlFile::XmlFile(uint32_t fileId, std::string_view text, Diagnostics& diags, std::string_view malformedCode) : fileId_(fileId), text_(text) {
  lineStarts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') lineStarts_.push_back(i + 1);
  pugi::xml_parse_result result = doc_.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!result) {
    diags.error(malformedCode, atOffset(static_cast<size_t>(std::max<ptrdiff_t>(result.offset, 0))),
                std::string("malformed XML: ") + result.description());
    return;
  }
  ok_ = true;
}

SourceLocation XmlFile::atOffset(size_t offset) const {
  offset = std::min(offset, text_.size());
  auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  size_t line = static_cast<size_t>(it - lineStarts_.begin());
  return {fileId_, static_cast<uint32_t>(line), static_cast<uint32_t>(offset - lineStarts_[line - 1] + 1)};
}

SourceLocation XmlFile::at(pugi::xml_node node) const {
  ptrdiff_t offset = node.offset_debug();
  if (offset < 0) return {fileId_, 0, 0};
  // For elements pugixml points at the name; the '<' before it is what an editor shows.
  if (node.type() == pugi::node_element && offset > 0) --offset;
  return atOffset(static_cast<size_t>(offset));
}

SourceLocation XmlFile::at(pugi::xml_node node, std::string_view attribute) const {
  // pugixml keeps no offsets for attributes: find `name=` inside the element's start tag.
  ptrdiff_t start = node.offset_debug();
  if (start < 0 || !node.attribute(std::string(attribute).c_str())) return at(node);
  size_t end = text_.find('>', static_cast<size_t>(start));
  std::string_view tag = text_.substr(static_cast<size_t>(start), end == std::string_view::npos ? end : end - start);
  for (size_t pos = tag.find(attribute); pos != std::string_view::npos; pos = tag.find(attribute, pos + 1)) {
    bool wordStart = pos > 0 && (tag[pos - 1] == ' ' || tag[pos - 1] == '\t' || tag[pos - 1] == '\n' || tag[pos - 1] == '\r');
    size_t after = pos + attribute.size();
    while (after < tag.size() && (tag[after] == ' ' || tag[after] == '=')) ++after;
    if (!wordStart || after >= tag.size() || (tag[after] != '"' && tag[after] != '\'')) continue;
    return atOffset(static_cast<size_t>(start) + after + 1);
  }
  return at(node);
}

std::string_view localName(pugi::xml_node node) {
  std::string_view name = node.name();
  size_t colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

pugi::xml_node child(pugi::xml_node node, std::string_view local) {
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element && localName(c) == local) return c;
  return {};
}

std::vector<pugi::xml_node> children(pugi::xml_node node, std::string_view local) {
  std::vector<pugi::xml_node> out;
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element && localName(c) == local) out.push_back(c);
  return out;
}

pugi::xml_node firstElement(pugi::xml_node node) {
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element) return c;
  return {};
}

namespace {
// Text wrappers are one or two elements deep (<xhtml:p>); a bound keeps hostile nesting off the stack.
constexpr int kMaxTextDepth = 8;

pugi::xml_node firstTextBelow(pugi::xml_node node, int depth) {
  if (depth > kMaxTextDepth) return {};
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
      std::string_view v = c.value();
      if (v.find_first_not_of(" \t\r\n") != std::string_view::npos) return c;
    } else if (c.type() == pugi::node_element) {
      if (pugi::xml_node t = firstTextBelow(c, depth + 1)) return t;
    }
  }
  return {};
}
}  // namespace

pugi::xml_node firstText(pugi::xml_node node) { return firstTextBelow(node, 0); }

std::string describe(pugi::xml_node node) {
  std::string out(localName(node));
  if (pugi::xml_attribute id = node.attribute("localId")) return out + " (localId " + id.value() + ")";
  if (pugi::xml_attribute name = node.attribute("name")) return out + " '" + name.value() + "'";
  return out;
}

}  // namespace virtcom::xml
