#pragma once
// Internal to the importer: the Importer whose methods are spread over import_project.cpp
// (project, POUs, global variables, configurations, vendor data), import_types.cpp (types,
// variables, initial values) and import_body.cpp (bodies: ST, LD/FBD networks, SFC).
#include <string>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/plcopen/ast_builder.hpp"
#include "lang/syntax/ast.hpp"
#include "lang/xml/xml_file.hpp"

namespace virtcom::plcopen {
// The XML helpers every part of the importer walks the document with (lang/xml).
using xml::child;
using xml::children;
using xml::describe;
using xml::firstElement;
using xml::firstText;
using xml::localName;
using xml::XmlFile;
}  // namespace virtcom::plcopen

namespace virtcom::plcopen::detail {

class Importer {
 public:
  Importer(XmlFile& xml, Diagnostics& diags, st::NodeId& nextNodeId, st::CompilationUnit& unit)
      : xml_(xml), diags_(diags), nextNodeId_(nextNodeId), build_(nextNodeId), unit_(unit) {}
  void importProject(pugi::xml_node project);

  // ---- shared with the network translator ----
  void error(std::string_view code, pugi::xml_node node, std::string message);
  void warning(std::string_view code, pugi::xml_node node, std::string message);
  void unsupported(pugi::xml_node node, std::string_view what);
  // Embedded ST at a text node (or an attribute value), parsed in place.
  st::ExprPtr expressionAt(pugi::xml_node textOrElement, std::string_view attribute = {});
  st::StmtList statementsAt(pugi::xml_node text);
  // The text content of `<expression>`/`<variable>`-like elements, parsed; null (after an X003)
  // if the element or its text is missing.
  st::ExprPtr expressionChild(pugi::xml_node owner, std::string_view element);
  XmlFile& xml() { return xml_; }
  AstBuilder& build() { return build_; }
  st::NodeId& nextNodeId() { return nextNodeId_; }
  Diagnostics& diags() { return diags_; }
  const st::CompilationUnit& unit() const { return unit_; }

 private:
  // ---- project (import_project.cpp) ----
  void importTypes(pugi::xml_node types);
  void importInstances(pugi::xml_node instances);
  void importProjectVendorData(pugi::xml_node addData);
  void importGlobalVarList(pugi::xml_node globalVars);
  st::Interface importInterfaceObject(pugi::xml_node interface);
  std::unique_ptr<st::Pou> importPou(pugi::xml_node pou);
  void importPouVendorData(pugi::xml_node addData, st::Pou& pou);
  std::unique_ptr<st::Pou> importMethod(pugi::xml_node method);
  void importActions(pugi::xml_node actions, st::Pou& pou);
  st::Configuration importConfiguration(pugi::xml_node configuration);
  st::Resource importResource(pugi::xml_node resource);
  st::TaskDecl importTask(pugi::xml_node task);
  st::ProgramConfig importPouInstance(pugi::xml_node instance, std::string taskName);
  void reportUnknownVendorData(pugi::xml_node data);
  // `{attribute ...}` pragmas stored as CODESYS `.../plcopenxml/attributes` data of `owner`.
  std::vector<st::Attribute> attributesIn(pugi::xml_node owner);
  // CODESYS EXTENDS/IMPLEMENTS of a POU, interface or STRUCT (vendor data of `owner`).
  struct Inheritance {
    std::string extends;
    std::vector<std::string> implements;
  };
  Inheritance inheritanceIn(pugi::xml_node owner);

  // ---- types and variables (import_types.cpp) ----
  st::TypeDecl importDataType(pugi::xml_node dataType);
  // `holder` is an element whose single element child is a type: <type>, <baseType>, <returnType>.
  st::TypeSpec typeIn(pugi::xml_node holder, int depth = 0);
  st::TypeSpec typeOf(pugi::xml_node typeElement, int depth);
  void importInterface(pugi::xml_node interface, st::Pou& pou);
  st::VarBlock varList(pugi::xml_node list, st::VarSection section);
  st::VarDecl variable(pugi::xml_node variable);
  st::ExprPtr initialValue(pugi::xml_node initialValue);
  st::ExprPtr value(pugi::xml_node valueElement, int depth);
  st::ExprPtr boundExpr(pugi::xml_node element, const char* attribute);

  // ---- bodies (import_body.cpp) ----
  // The statements of a <body>; graphical bodies may add hidden variables to `owner`
  // (edge memories, block results), named with `prefix` so an action's never clash with the POU's.
  st::StmtList importBody(pugi::xml_node body, st::Pou& owner, std::string_view prefix);
  // A graphical SFC body (import_sfc.cpp): read into the SFC model and lowered into `pou`.
  void importChart(pugi::xml_node sfc, pugi::xml_node pouNode, st::Pou& pou);

  XmlFile& xml_;
  Diagnostics& diags_;
  st::NodeId& nextNodeId_;
  AstBuilder build_;
  st::CompilationUnit& unit_;
  pugi::xml_node currentPou_;  // the <pou> being imported (its <transitions> serve SFC bodies)
};

}  // namespace virtcom::plcopen::detail
