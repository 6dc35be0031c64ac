// The project level: types, POUs, global variables, configurations and vendor data; see
// import_internal.hpp.
#include <algorithm>
#include <optional>

#include "core/ascii.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/import_internal.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/plcopen/twincat_file.hpp"
#include "lang/st/parse/parser.hpp"

namespace virtcom::plcopen {

namespace detail {

namespace {

// What the importer does with a vendor <data name="..."> block (CODESYS writes most of a
// project's non-standard parts this way).
enum class VendorData { Ignore, GlobalVars, Method, Inheritance, Pou, DataType, Interface, Unsupported };

struct VendorDataEntry {
  std::string_view name;
  VendorData handling;
  std::string_view what;  // for Unsupported: how the message names it
};

constexpr std::string_view kCodesys = "http://www.3s-software.com/plcopenxml/";
constexpr VendorDataEntry kVendorData[] = {
    {"globalvars", VendorData::GlobalVars, ""},
    {"attributes", VendorData::Ignore, ""},  // read with their owner: attributesIn()
    {"method", VendorData::Method, ""},
    // Redundant with the structured interface, or editor metadata.
    {"interfaceasplaintext", VendorData::Ignore, ""},
    {"objectid", VendorData::Ignore, ""},
    {"projectstructure", VendorData::Ignore, ""},
    {"projectinformation", VendorData::Ignore, ""},
    {"buildproperties", VendorData::Ignore, ""},
    {"folder", VendorData::Ignore, ""},
    {"tasksettings", VendorData::Ignore, ""},
    {"pouinheritance", VendorData::Inheritance, ""},
    {"datatypeinheritance", VendorData::Inheritance, ""},
    // The objects of an application: CODESYS writes them into its resource's <addData>.
    {"pou", VendorData::Pou, ""},
    {"datatype", VendorData::DataType, ""},
    {"interface", VendorData::Interface, ""},
    {"property", VendorData::Unsupported, "CODESYS PROPERTY"},
    {"action", VendorData::Unsupported, "CODESYS action of this form"},
    {"transition", VendorData::Unsupported, "CODESYS transition of this form"},
};

const VendorDataEntry* findVendorData(std::string_view name) {
  if (name.substr(0, kCodesys.size()) != kCodesys) return nullptr;
  name.remove_prefix(kCodesys.size());
  for (const auto& entry : kVendorData)
    if (entry.name == name) return &entry;
  return nullptr;
}

// TC6 leaves a task interval's notation open ("a constant duration as defined in the IEC or a
// variable name"); CODESYS writes ISO 8601 durations (`PT0.02S`, `P0DT0H0M0.02S`) and TC6 1.0
// typed it xsd:time (`00:00:00.020`). Those two become the IEC literal; anything else is ST.
std::optional<std::string> intervalAsIecLiteral(std::string_view text) {
  auto number = [&](size_t& i) {
    size_t start = i;
    while (i < text.size() && (isAsciiDigit(text[i]) || text[i] == '.')) ++i;
    return text.substr(start, i - start);
  };
  std::string out = "T#";
  size_t i = 0;
  if (!text.empty() && text[0] == 'P') {
    bool inTime = false;
    for (i = 1; i < text.size();) {
      if (text[i] == 'T' && !inTime) {
        inTime = true;
        ++i;
        continue;
      }
      std::string_view value = number(i);
      if (value.empty() || i == text.size()) return std::nullopt;
      char unit = text[i++];
      // Years and months have no fixed length: not an interval.
      const char* iecUnit = !inTime ? (unit == 'D' ? "d" : nullptr)
                                    : unit == 'H' ? "h" : unit == 'M' ? "m" : unit == 'S' ? "s" : nullptr;
      if (!iecUnit) return std::nullopt;
      out.append(value).append(iecUnit);
    }
    return out.size() > 2 ? std::optional<std::string>(out) : std::nullopt;
  }
  static constexpr const char* kTimeUnits[] = {"h", "m", "s"};
  for (const char* unit : kTimeUnits) {
    std::string_view value = number(i);
    if (value.empty()) return std::nullopt;
    out.append(value).append(unit);
    if (*unit != 's' && (i == text.size() || text[i++] != ':')) return std::nullopt;
  }
  return i == text.size() ? std::optional<std::string>(out) : std::nullopt;
}

bool pouKindOf(std::string_view pouType, st::PouKind& kind) {
  if (pouType == "program") kind = st::PouKind::Program;
  else if (pouType == "function") kind = st::PouKind::Function;
  else if (pouType == "functionBlock") kind = st::PouKind::FunctionBlock;
  else return false;
  return true;
}

}  // namespace

void Importer::error(std::string_view code, pugi::xml_node node, std::string message) {
  diags_.error(code, xml_.at(node), std::move(message));
}

void Importer::warning(std::string_view code, pugi::xml_node node, std::string message) {
  diags_.warning(code, xml_.at(node), std::move(message));
}

void Importer::unsupported(pugi::xml_node node, std::string_view what) {
  std::string where = node.attribute("localId") ? " (" + describe(node) + ")" : "";
  error(diag::X004, node, std::string(what) + where + " is not supported");
}

st::ExprPtr Importer::expressionAt(pugi::xml_node node, std::string_view attribute) {
  if (!attribute.empty()) {
    std::string_view text = node.attribute(std::string(attribute).c_str()).value();
    return st::parseExpression(xml_.fileId(), xml_.at(node, attribute), text, diags_, nextNodeId_);
  }
  pugi::xml_node text = node.type() == pugi::node_element ? firstText(node) : node;
  if (!text) {
    error(diag::X003, node, "<" + std::string(localName(node)) + "> holds no expression");
    return build_.name("", xml_.at(node));
  }
  return st::parseExpression(xml_.fileId(), xml_.at(text), text.value(), diags_, nextNodeId_);
}

st::StmtList Importer::statementsAt(pugi::xml_node text) {
  return st::parseStatements(xml_.fileId(), xml_.at(text), text.value(), diags_, nextNodeId_);
}

st::ExprPtr Importer::expressionChild(pugi::xml_node owner, std::string_view element) {
  pugi::xml_node holder = child(owner, element);
  if (!holder || !firstText(holder)) {
    error(diag::X003, owner, describe(owner) + " has no <" + std::string(element) + ">");
    return nullptr;
  }
  return expressionAt(holder);
}

void Importer::importProject(pugi::xml_node project) {
  if (localName(project) != "project") {
    error(diag::X002, project, "the root element is <" + std::string(localName(project)) +
                                   ">; a PLCopen TC6 XML file starts with <project xmlns=\"http://www.plcopen.org/xml/tc6_0201\">");
    return;
  }
  for (pugi::xml_node part = project.first_child(); part; part = part.next_sibling()) {
    if (part.type() != pugi::node_element) continue;
    std::string_view name = localName(part);
    if (name == "types") importTypes(part);
    else if (name == "instances") importInstances(part);
    else if (name == "addData") importProjectVendorData(part);
    else if (name != "fileHeader" && name != "contentHeader" && name != "documentation")
      unsupported(part, "project element <" + std::string(name) + ">");
  }
}

void Importer::importTypes(pugi::xml_node types) {
  for (pugi::xml_node t : children(child(types, "dataTypes"), "dataType")) unit_.types.push_back(importDataType(t));
  for (pugi::xml_node p : children(child(types, "pous"), "pou"))
    if (auto pou = importPou(p)) unit_.pous.push_back(std::move(pou));
}

std::unique_ptr<st::Pou> Importer::importPou(pugi::xml_node node) {
  auto pou = std::make_unique<st::Pou>();
  pou->name = node.attribute("name").value();
  pou->loc = xml_.at(node, "name");
  pou->endLoc = pou->loc;
  if (pou->name.empty()) error(diag::X003, node, "<pou> has no 'name' attribute");
  std::string_view pouType = node.attribute("pouType").value();
  if (!pouKindOf(pouType, pou->kind)) {
    error(diag::X005, node, describe(node) + ": pouType '" + std::string(pouType) +
                                "' is not one of program, function, functionBlock");
    return nullptr;
  }
  pugi::xml_node interface = child(node, "interface");
  if (interface) importInterface(interface, *pou);
  // CODESYS writes EXTENDS/IMPLEMENTS as vendor data of the interface (or of the POU).
  for (pugi::xml_node owner : {interface, node}) {
    Inheritance inherited = inheritanceIn(owner);
    if (!inherited.extends.empty()) pou->extends = std::move(inherited.extends);
    for (std::string& i : inherited.implements) pou->implements.push_back(std::move(i));
  }
  pou->attributes = attributesIn(node);
  if (pou->kind == st::PouKind::Function && !pou->hasReturnType)
    error(diag::X003, node, describe(node) + " is a function without <returnType> in its <interface>");
  // Actions first: an SFC body's lowering refers to them.
  if (pugi::xml_node actions = child(node, "actions")) importActions(actions, *pou);
  currentPou_ = node;
  std::vector<pugi::xml_node> bodies = children(node, "body");
  pou->hasBody = !bodies.empty();
  if (bodies.empty()) error(diag::X003, node, describe(node) + " has no <body>");
  for (pugi::xml_node body : bodies)
    for (st::StmtPtr& stmt : importBody(body, *pou, "")) pou->body.push_back(std::move(stmt));
  if (pugi::xml_node addData = child(node, "addData")) importPouVendorData(addData, *pou);
  return pou;
}

void Importer::importActions(pugi::xml_node actions, st::Pou& pou) {
  for (pugi::xml_node node : children(actions, "action")) {
    auto action = std::make_unique<st::Pou>();
    action->kind = st::PouKind::Action;
    action->name = node.attribute("name").value();
    action->loc = xml_.at(node, "name");
    action->endLoc = action->loc;
    action->hasBody = true;
    if (action->name.empty()) error(diag::X003, node, "<action> has no 'name' attribute");
    pugi::xml_node body = child(node, "body");
    if (!body) error(diag::X003, node, describe(node) + " has no <body>");
    else action->body = importBody(body, pou, action->name + "_");
    pou.actions.push_back(std::move(action));
  }
}

std::unique_ptr<st::Pou> Importer::importMethod(pugi::xml_node node) {
  auto method = std::make_unique<st::Pou>();
  method->kind = st::PouKind::Method;
  method->name = node.attribute("name").value();
  method->loc = xml_.at(node, "name");
  method->endLoc = method->loc;
  if (method->name.empty()) error(diag::X003, node, "<Method> has no 'name' attribute");
  if (pugi::xml_node interface = child(node, "interface")) importInterface(interface, *method);
  pugi::xml_node body = child(node, "body");
  method->hasBody = static_cast<bool>(body);
  if (body) method->body = importBody(body, *method, "");
  return method;
}

std::vector<st::Attribute> Importer::attributesIn(pugi::xml_node owner) {
  std::vector<st::Attribute> out;
  for (pugi::xml_node data : children(child(owner, "addData"), "data")) {
    const VendorDataEntry* entry = findVendorData(data.attribute("name").value());
    if (!entry || entry->name != "attributes") continue;
    for (pugi::xml_node a : children(child(data, "Attributes"), "Attribute"))
      out.push_back({a.attribute("Name").value(), a.attribute("Value").value()});
  }
  return out;
}

Importer::Inheritance Importer::inheritanceIn(pugi::xml_node owner) {
  Inheritance out;
  for (pugi::xml_node data : children(child(owner, "addData"), "data")) {
    const VendorDataEntry* entry = findVendorData(data.attribute("name").value());
    if (!entry || entry->handling != VendorData::Inheritance) continue;
    pugi::xml_node inheritance = child(data, "Inheritance");
    if (pugi::xml_node extends = child(inheritance, "Extends"); extends && firstText(extends))
      out.extends = std::string(trimAscii(firstText(extends).value()));
    for (pugi::xml_node implements : children(inheritance, "Implements"))
      if (firstText(implements)) out.implements.emplace_back(trimAscii(firstText(implements).value()));
  }
  return out;
}

void Importer::reportUnknownVendorData(pugi::xml_node data) {
  // handleUnknown="discard"/"preserve" declares the data optional for other tools (TC6 §2.2).
  if (std::string_view(data.attribute("handleUnknown").value()) != "implementation") return;
  warning(diag::X101, data, std::string("vendor data '") + data.attribute("name").value() +
                                "' is not supported and was ignored");
}

void Importer::importPouVendorData(pugi::xml_node addData, st::Pou& pou) {
  for (pugi::xml_node data : children(addData, "data")) {
    const VendorDataEntry* entry = findVendorData(data.attribute("name").value());
    if (!entry) {
      reportUnknownVendorData(data);
    } else if (entry->handling == VendorData::Method && pou.kind != st::PouKind::Function) {
      for (pugi::xml_node m : children(data, "Method")) pou.methods.push_back(importMethod(m));
    } else if (entry->handling == VendorData::Unsupported || entry->handling == VendorData::Method) {
      unsupported(data, entry->handling == VendorData::Method ? "a METHOD of a FUNCTION" : entry->what);
    } else if (entry->handling != VendorData::Ignore && entry->handling != VendorData::Inheritance) {
      unsupported(data, "this vendor data inside a POU");
    }
  }
}

void Importer::importGlobalVarList(pugi::xml_node list) {
  // One list may come as several <globalVars> of the same name (e.g. its CONSTANT part).
  std::string name = list.attribute("name").value();
  auto same = std::find_if(unit_.globals.begin(), unit_.globals.end(),
                           [&](const st::GlobalVarList& g) { return g.name == name; });
  if (same == unit_.globals.end()) {
    st::GlobalVarList gvl;
    gvl.name = name;
    gvl.loc = xml_.at(list, "name");
    unit_.globals.push_back(std::move(gvl));
    same = unit_.globals.end() - 1;
  }
  same->blocks.push_back(varList(list, st::VarSection::Global));
  for (st::Attribute& a : attributesIn(list)) same->attributes.push_back(std::move(a));
}

void Importer::importProjectVendorData(pugi::xml_node addData) {
  for (pugi::xml_node data : children(addData, "data")) {
    const VendorDataEntry* entry = findVendorData(data.attribute("name").value());
    if (!entry) {
      reportUnknownVendorData(data);
      continue;
    }
    switch (entry->handling) {
      case VendorData::GlobalVars:
        for (pugi::xml_node list : children(data, "globalVars")) importGlobalVarList(list);
        break;
      case VendorData::Pou:
        for (pugi::xml_node p : children(data, "pou"))
          if (auto pou = importPou(p)) unit_.pous.push_back(std::move(pou));
        break;
      case VendorData::DataType:
        for (pugi::xml_node t : children(data, "dataType")) unit_.types.push_back(importDataType(t));
        break;
      case VendorData::Interface:
        for (pugi::xml_node i : children(data, "Interface")) unit_.interfaces.push_back(importInterfaceObject(i));
        break;
      case VendorData::Ignore: break;
      default: unsupported(data, entry->handling == VendorData::Method ? "a METHOD outside a POU" : entry->what);
    }
  }
}

// A CODESYS/TwinCAT INTERFACE: method prototypes (<Methods><Method>, or method vendor data as
// a POU carries it) and the interfaces it extends.
st::Interface Importer::importInterfaceObject(pugi::xml_node node) {
  st::Interface itf;
  itf.name = node.attribute("name").value();
  itf.loc = xml_.at(node, "name");
  if (itf.name.empty()) error(diag::X003, node, "<Interface> has no 'name' attribute");
  std::vector<pugi::xml_node> methods = children(child(node, "Methods"), "Method");
  for (pugi::xml_node data : children(child(node, "addData"), "data")) {
    const VendorDataEntry* entry = findVendorData(data.attribute("name").value());
    if (entry && entry->handling == VendorData::Method)
      for (pugi::xml_node m : children(data, "Method")) methods.push_back(m);
    else if (entry && entry->handling == VendorData::Unsupported) unsupported(data, entry->what);
  }
  for (pugi::xml_node m : methods) {
    auto method = importMethod(m);
    method->hasBody = false;  // a prototype: an implementing FB's METHOD has the body
    method->body.clear();
    itf.methods.push_back(std::move(method));
  }
  Inheritance inherited = inheritanceIn(node);
  if (!inherited.extends.empty()) itf.extends.push_back(inherited.extends);
  for (std::string& base : inherited.implements) itf.extends.push_back(std::move(base));
  return itf;
}

void Importer::importInstances(pugi::xml_node instances) {
  for (pugi::xml_node cfg : children(child(instances, "configurations"), "configuration"))
    unit_.configurations.push_back(importConfiguration(cfg));
}

st::Configuration Importer::importConfiguration(pugi::xml_node node) {
  st::Configuration cfg;
  cfg.name = node.attribute("name").value();
  cfg.loc = xml_.at(node, "name");
  for (pugi::xml_node part = node.first_child(); part; part = part.next_sibling()) {
    if (part.type() != pugi::node_element) continue;
    std::string_view name = localName(part);
    if (name == "resource") cfg.resources.push_back(importResource(part));
    else if (name == "globalVars" && part.attribute("name")) importGlobalVarList(part);
    else if (name == "globalVars") cfg.globals.push_back(varList(part, st::VarSection::Global));
    else if (name == "addData") importProjectVendorData(part);
    else if (name != "documentation")
      unsupported(part, "configuration element <" + std::string(name) + ">");
  }
  return cfg;
}

st::Resource Importer::importResource(pugi::xml_node node) {
  st::Resource res;
  res.name = node.attribute("name").value();
  res.loc = xml_.at(node, "name");
  for (pugi::xml_node part = node.first_child(); part; part = part.next_sibling()) {
    if (part.type() != pugi::node_element) continue;
    std::string_view name = localName(part);
    if (name == "task") {
      res.tasks.push_back(importTask(part));
      for (pugi::xml_node inst : children(part, "pouInstance"))
        res.programs.push_back(importPouInstance(inst, res.tasks.back().name));
    } else if (name == "pouInstance") {
      res.programs.push_back(importPouInstance(part, ""));
    } else if (name == "globalVars" && part.attribute("name")) {
      importGlobalVarList(part);
    } else if (name == "globalVars") {
      res.globals.push_back(varList(part, st::VarSection::Global));
    } else if (name == "addData") {
      importProjectVendorData(part);
    } else if (name != "documentation") {
      unsupported(part, "resource element <" + std::string(name) + ">");
    }
  }
  return res;
}

st::TaskDecl Importer::importTask(pugi::xml_node node) {
  st::TaskDecl task;
  task.name = node.attribute("name").value();
  task.loc = xml_.at(node, "name");
  if (task.name.empty()) error(diag::X003, node, "<task> has no 'name' attribute");
  static constexpr std::pair<const char*, const char*> kSettings[] = {
      {"interval", "INTERVAL"}, {"priority", "PRIORITY"}, {"single", "SINGLE"}};
  for (const auto& [attribute, setting] : kSettings) {
    if (!node.attribute(attribute)) continue;
    st::CallArg arg;
    arg.name = setting;
    arg.loc = xml_.at(node, attribute);
    std::optional<std::string> literal;
    if (setting == std::string_view("INTERVAL")) literal = intervalAsIecLiteral(node.attribute(attribute).value());
    arg.value = literal ? st::parseExpression(xml_.fileId(), arg.loc, *literal, diags_, nextNodeId_)
                        : expressionAt(node, attribute);
    task.settings.push_back(std::move(arg));
  }
  return task;
}

st::ProgramConfig Importer::importPouInstance(pugi::xml_node node, std::string taskName) {
  st::ProgramConfig prog;
  prog.instanceName = node.attribute("name").value();
  // TC6 1.0 named the attribute `type`.
  prog.typeName = node.attribute(node.attribute("typeName") ? "typeName" : "type").value();
  prog.taskName = std::move(taskName);
  prog.loc = xml_.at(node);
  // CODESYS writes typeName="" for a program called by its own name.
  if (prog.typeName.empty() && node.attribute("typeName")) prog.typeName = prog.instanceName;
  if (prog.instanceName.empty() || prog.typeName.empty())
    error(diag::X003, node, "<pouInstance> needs both 'name' and 'typeName' attributes");
  return prog;
}

}  // namespace detail

st::CompilationUnit importProject(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId) {
  st::CompilationUnit unit;
  unit.fileId = fileId;
  XmlFile xml(fileId, text, diags, diag::X001);
  if (!xml.ok()) return unit;
  detail::Importer importer(xml, diags, nextNodeId, unit);
  importer.importProject(xml.root());
  return unit;
}

bool isPlcopenPath(std::string_view path) {
  return iendsWithAscii(path, ".xml");
}

st::SourceInput sourceInput(std::string path, std::string text) {
  st::FrontEnd frontEnd;
  if (isPlcopenPath(path)) frontEnd = importProject;
  else if (isTwinCatPath(path)) frontEnd = importTwinCatFile;
  else if (ad::isDiagramPath(path)) frontEnd = ad::importDiagrams;
  else if (ad::isXmlDiagramPath(path)) frontEnd = ad::importXmlDiagrams;
  return {std::move(path), std::move(text), std::move(frontEnd)};
}

}  // namespace virtcom::plcopen
