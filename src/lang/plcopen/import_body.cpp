// POU, action and method bodies; see import_internal.hpp.
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/il_translate.hpp"
#include "lang/plcopen/import_internal.hpp"
#include "lang/plcopen/network_translate.hpp"

namespace virtcom::plcopen::detail {

st::StmtList Importer::importBody(pugi::xml_node body, st::Pou& owner, std::string_view prefix) {
  st::StmtList out;
  for (pugi::xml_node lang = body.first_child(); lang; lang = lang.next_sibling()) {
    if (lang.type() != pugi::node_element) continue;
    std::string_view name = localName(lang);
    if (name == "ST") {
      if (pugi::xml_node text = firstText(lang))
        for (st::StmtPtr& s : statementsAt(text)) out.push_back(std::move(s));
    } else if (name == "LD" || name == "FBD") {
      Network net = readNetwork(*this, lang, name == "LD");
      for (st::StmtPtr& s : translateNetwork(*this, net, owner, prefix)) out.push_back(std::move(s));
    } else if (name == "IL") {
      if (pugi::xml_node text = firstText(lang))
        for (st::StmtPtr& s : translateIl(*this, text, owner, prefix)) out.push_back(std::move(s));
    } else if (name == "SFC") {
      if (!prefix.empty() || owner.kind == st::PouKind::Method) unsupported(lang, "an SFC body of an action or method");
      else importChart(lang, currentPou_, owner);
    } else if (name != "addData" && name != "documentation") {
      unsupported(lang, "body language <" + std::string(name) + ">");
    }
  }
  return out;
}

}  // namespace virtcom::plcopen::detail
