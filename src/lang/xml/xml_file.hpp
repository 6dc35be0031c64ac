#pragma once
// An XML file parsed with pugixml, and the way back from its nodes to line:col locations, shared
// by the XML front ends (PLCopen TC6 and TwinCAT files in lang/plcopen, AD-XML in lang/ad).
// PLCopen files come with and without namespace prefixes (`<project xmlns="...tc6_0201">`,
// `<xhtml:p>`), so elements are matched by their local name.
#include <pugixml.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::xml {

class XmlFile {
 public:
  // Parses `text` (which must outlive this object). A malformed document is reported with
  // `malformedCode` (the front end's own code, e.g. X001) at the offending byte; ok() then
  // returns false. Never throws.
  XmlFile(uint32_t fileId, std::string_view text, Diagnostics& diags, std::string_view malformedCode);
  bool ok() const { return ok_; }
  pugi::xml_node root() const { return doc_.document_element(); }
  uint32_t fileId() const { return fileId_; }

  // An element: its '<'; a text or CDATA node: its first character.
  SourceLocation at(pugi::xml_node node) const;
  // The first character of the attribute's value, or the element when the attribute is absent.
  SourceLocation at(pugi::xml_node node, std::string_view attribute) const;
  SourceLocation atOffset(size_t offset) const;

 private:
  uint32_t fileId_;
  std::string_view text_;
  pugi::xml_document doc_;
  std::vector<size_t> lineStarts_;
  bool ok_ = false;
};

// "project" for both <project> and <ppx:project>.
std::string_view localName(pugi::xml_node node);
// The first child element with this local name (null node if none).
pugi::xml_node child(pugi::xml_node node, std::string_view local);
// Every child element with this local name, in document order.
std::vector<pugi::xml_node> children(pugi::xml_node node, std::string_view local);
// The first element child, whatever its name (null node if none).
pugi::xml_node firstElement(pugi::xml_node node);
// The first non-blank text or CDATA node below `node` (depth first), e.g. the text of
// <ST><xhtml:p><![CDATA[...]]></xhtml:p></ST>; null node if there is none.
pugi::xml_node firstText(pugi::xml_node node);
// How diagnostics name an element: `contact (localId 5)`, `pou 'MAIN'`, or just `variable`.
std::string describe(pugi::xml_node node);

}  // namespace virtcom::xml
