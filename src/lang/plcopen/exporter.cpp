#include "lang/plcopen/exporter.hpp"

#include <pugixml.hpp>

#include <span>
#include <sstream>

#include "core/ascii.hpp"
#include "core/iec_value.hpp"
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/export_internal.hpp"
#include "lang/syntax/printer.hpp"

namespace virtcom::plcopen {

namespace {

constexpr const char* kMethodData = "http://www.3s-software.com/plcopenxml/method";
constexpr const char* kGlobalVarsData = "http://www.3s-software.com/plcopenxml/globalvars";
constexpr const char* kAttributesData = "http://www.3s-software.com/plcopenxml/attributes";

pugi::xml_node addDataOf(pugi::xml_node node) {
  pugi::xml_node existing = node.child("addData");
  return existing ? existing : node.append_child("addData");
}

// `{attribute 'name' := 'value'}` pragmas in the form CODESYS writes them.
void writeAttributes(pugi::xml_node owner, const std::vector<st::Attribute>& attributes) {
  if (attributes.empty()) return;
  pugi::xml_node data = addDataOf(owner).append_child("data");
  data.append_attribute("name") = kAttributesData;
  data.append_attribute("handleUnknown") = "implementation";
  pugi::xml_node list = data.append_child("Attributes");
  for (const auto& a : attributes) {
    pugi::xml_node attribute = list.append_child("Attribute");
    attribute.append_attribute("Name") = a.name.c_str();
    attribute.append_attribute("Value") = a.value.c_str();
  }
}

const char* varListElement(st::VarSection section) {
  switch (section) {
    case st::VarSection::Input: return "inputVars";
    case st::VarSection::Output: return "outputVars";
    case st::VarSection::InOut: return "inOutVars";
    case st::VarSection::Var: return "localVars";
    case st::VarSection::Temp: return "tempVars";
    case st::VarSection::External: return "externalVars";
    case st::VarSection::Global: return "globalVars";
    case st::VarSection::Inst: case st::VarSection::Stat: return nullptr;
  }
  return nullptr;
}

const char* pouTypeName(st::PouKind kind) {
  switch (kind) {
    case st::PouKind::Program: return "program";
    case st::PouKind::Function: return "function";
    case st::PouKind::FunctionBlock: return "functionBlock";
    default: return nullptr;
  }
}

// TC6 spells the elementary types as elements (<INT/>); the long date/time names have short forms.
std::string elementaryElement(const std::string& name) {
  const std::string up = asciiUpper(name);
  if (up == "TIME_OF_DAY") return "TOD";
  if (up == "DATE_AND_TIME") return "DT";
  ElemType type{};
  if (up == "STRING" || up == "WSTRING" || !elemTypeByName(up, type)) return {};
  return up;
}

class Exporter {
 public:
  Exporter(const ExportOptions& options, Diagnostics& diags) : options_(options), diags_(diags) {}
  std::string run(const std::vector<const st::CompilationUnit*>& units);

 private:
  void unsupported(SourceLocation loc, const std::string& what) {
    diags_.error(diag::X004, loc, what + " cannot be written to PLCopen TC6 XML");
  }
  void pou(pugi::xml_node pous, const st::Pou& p);
  // `lowered`: the variable blocks a chart's lowering added, not written.
  void interface(pugi::xml_node parent, const st::Pou& p, st::ChartSource::Range lowered = {});
  void body(pugi::xml_node node, const st::Pou& p);
  void varList(pugi::xml_node parent, const st::VarBlock& block, const char* element);
  void variable(pugi::xml_node list, const st::VarDecl& decl);
  void type(pugi::xml_node holder, const st::TypeSpec& spec);
  void value(pugi::xml_node holder, const st::Expr& init);
  void stBody(pugi::xml_node parent, std::span<const st::StmtPtr> body);
  void configuration(pugi::xml_node configurations, const st::Configuration& cfg);

  const ExportOptions& options_;
  Diagnostics& diags_;
};

void Exporter::stBody(pugi::xml_node parent, std::span<const st::StmtPtr> body) {
  detail::writeStText(parent.append_child("body").append_child("ST"), st::printStatements(body));
}

void Exporter::type(pugi::xml_node holder, const st::TypeSpec& spec) {
  switch (spec.kind) {
    case st::TypeSpecKind::Named: {
      std::string element = elementaryElement(spec.name);
      if (!element.empty()) holder.append_child(element.c_str());
      else holder.append_child("derived").append_attribute("name") = spec.name.c_str();
      break;
    }
    case st::TypeSpecKind::String: {
      pugi::xml_node s = holder.append_child(spec.wide ? "wstring" : "string");
      if (spec.length) s.append_attribute("length") = st::printExpr(*spec.length).c_str();
      break;
    }
    case st::TypeSpecKind::Array: {
      pugi::xml_node a = holder.append_child("array");
      for (const auto& dim : spec.dims) {
        if (!dim.lo || !dim.hi) return unsupported(spec.loc, "ARRAY[*]");
        pugi::xml_node d = a.append_child("dimension");
        d.append_attribute("lower") = st::printExpr(*dim.lo).c_str();
        d.append_attribute("upper") = st::printExpr(*dim.hi).c_str();
      }
      type(a.append_child("baseType"), *spec.element);
      break;
    }
    case st::TypeSpecKind::Pointer: type(holder.append_child("pointer").append_child("baseType"), *spec.element); break;
    case st::TypeSpecKind::Reference: unsupported(spec.loc, "REFERENCE TO"); break;
    case st::TypeSpecKind::Subrange: {
      pugi::xml_node r = holder.append_child("subrangeSigned");
      pugi::xml_node range = r.append_child("range");
      range.append_attribute("lower") = st::printExpr(*spec.lo).c_str();
      range.append_attribute("upper") = st::printExpr(*spec.hi).c_str();
      type(r.append_child("baseType"), *spec.element);
      break;
    }
    case st::TypeSpecKind::Enum: {
      pugi::xml_node e = holder.append_child("enum");
      pugi::xml_node values = e.append_child("values");
      for (const auto& v : spec.enumValues) {
        pugi::xml_node value = values.append_child("value");
        value.append_attribute("name") = v.name.c_str();
        if (v.value) value.append_attribute("value") = st::printExpr(*v.value).c_str();
      }
      if (!spec.name.empty()) {
        st::TypeSpec base;
        base.name = spec.name;
        type(e.append_child("baseType"), base);
      }
      break;
    }
    case st::TypeSpecKind::Struct: {
      if (!spec.name.empty()) unsupported(spec.loc, "STRUCT EXTENDS");
      if (spec.isUnion) unsupported(spec.loc, "UNION");
      pugi::xml_node s = holder.append_child("struct");
      for (const auto& field : spec.fields) variable(s, field);
      break;
    }
  }
}

void Exporter::value(pugi::xml_node holder, const st::Expr& init) {
  if (init.kind == st::ExprKind::ArrayInit) {
    pugi::xml_node a = holder.append_child("arrayValue");
    for (const auto& item : init.items) {
      pugi::xml_node v = a.append_child("value");
      const st::Expr* inner = item.get();
      if (item->kind == st::ExprKind::Repeat) {
        v.append_attribute("repetitionValue") = std::to_string(item->intValue).c_str();
        inner = item->lhs.get();
      }
      if (inner) value(v, *inner);
      else v.append_child("simpleValue").append_attribute("value") = "0";
    }
  } else if (init.kind == st::ExprKind::StructInit) {
    pugi::xml_node s = holder.append_child("structValue");
    for (const auto& arg : init.args) {
      pugi::xml_node v = s.append_child("value");
      v.append_attribute("member") = arg.name.c_str();
      if (arg.value) value(v, *arg.value);
    }
  } else {
    holder.append_child("simpleValue").append_attribute("value") = st::printExpr(init).c_str();
  }
}

void Exporter::variable(pugi::xml_node list, const st::VarDecl& decl) {
  if (!decl.fbInitArgs.empty()) unsupported(decl.loc, "FB_init arguments of an instance");
  if (decl.edge != st::EdgeKind::None) unsupported(decl.edgeLoc, "R_EDGE / F_EDGE on an input");
  for (const auto& name : decl.names) {
    pugi::xml_node v = list.append_child("variable");
    v.append_attribute("name") = name.name.c_str();
    if (!decl.location.empty()) v.append_attribute("address") = decl.location.c_str();
    type(v.append_child("type"), decl.type);
    if (decl.init) value(v.append_child("initialValue"), *decl.init);
    writeAttributes(v, decl.attributes);
  }
}

void Exporter::varList(pugi::xml_node parent, const st::VarBlock& block, const char* element) {
  pugi::xml_node list = parent.append_child(element);
  if (block.constant) list.append_attribute("constant") = "true";
  if (block.retain) list.append_attribute("retain") = "true";
  if (block.persistent) list.append_attribute("persistent") = "true";
  for (const auto& decl : block.vars) variable(list, decl);
}

void Exporter::interface(pugi::xml_node parent, const st::Pou& p, st::ChartSource::Range lowered) {
  pugi::xml_node i = parent.append_child("interface");
  if (p.hasReturnType) type(i.append_child("returnType"), p.returnType);
  for (size_t k = 0; k < p.varBlocks.size(); ++k) {
    if (lowered.contains(k)) continue;
    const st::VarBlock& block = p.varBlocks[k];
    const char* element = varListElement(block.section);
    if (!element) unsupported(block.loc, "VAR_INST / VAR_STAT");
    else varList(i, block, element);
  }
}

void Exporter::pou(pugi::xml_node pous, const st::Pou& p) {
  const char* pouType = pouTypeName(p.kind);
  if (!pouType) return unsupported(p.loc, "this POU kind");
  if (!p.extends.empty() || !p.implements.empty()) unsupported(p.loc, "EXTENDS / IMPLEMENTS");
  if (!p.properties.empty()) unsupported(p.properties.front().loc, "PROPERTY");
  pugi::xml_node node = pous.append_child("pou");
  node.append_attribute("name") = p.name.c_str();
  node.append_attribute("pouType") = pouType;
  // A chart is written as a chart, without what its lowering added to the POU.
  st::ChartSource lowered = p.chart.value_or(st::ChartSource{});
  interface(node, p, lowered.varBlocks);
  pugi::xml_node actions;
  for (size_t k = 0; k < p.actions.size(); ++k) {
    if (lowered.actions.contains(k)) continue;
    if (!actions) actions = node.append_child("actions");
    pugi::xml_node action = actions.append_child("action");
    action.append_attribute("name") = p.actions[k]->name.c_str();
    body(action, *p.actions[k]);
  }
  body(node, p);
  writeAttributes(node, p.attributes);
  for (const auto& m : p.methods) {
    if (m->access != st::Access::Default || m->isAbstract || m->isFinal || !m->hasBody)
      unsupported(m->loc, "an access modifier, ABSTRACT, FINAL or a missing body of a METHOD");
    pugi::xml_node data = addDataOf(node).append_child("data");
    data.append_attribute("name") = kMethodData;
    data.append_attribute("handleUnknown") = "implementation";
    pugi::xml_node method = data.append_child("Method");
    method.append_attribute("name") = m->name.c_str();
    interface(method, *m);
    stBody(method, m->body);
  }
}

// The body (of a POU or an action); rungs as an LD body; with a chart, the POU's statements before and after the lowered ones become ST
// bodies around the SFC body (bodies run in document order).
void Exporter::body(pugi::xml_node node, const st::Pou& p) {
  if (p.ladder) return detail::writeLadderBody(node, *p.ladder);  // drawn as rungs, written as rungs
  if (!p.chart) return stBody(node, p.body);
  const st::ChartSource& chart = *p.chart;
  detail::writeChartTransitions(node, *chart.chart);
  std::span<const st::StmtPtr> all(p.body);
  if (chart.statements.begin > 0) stBody(node, all.first(chart.statements.begin));
  detail::writeChartBody(node, *chart.chart);
  if (chart.statements.end < all.size()) stBody(node, all.subspan(chart.statements.end));
}

void Exporter::configuration(pugi::xml_node configurations, const st::Configuration& cfg) {
  pugi::xml_node c = configurations.append_child("configuration");
  c.append_attribute("name") = cfg.name.c_str();
  for (const auto& res : cfg.resources) {
    pugi::xml_node r = c.append_child("resource");
    r.append_attribute("name") = res.name.c_str();
    for (const auto& task : res.tasks) {
      pugi::xml_node t = r.append_child("task");
      t.append_attribute("name") = task.name.c_str();
      for (const auto& s : task.settings) {
        const std::string key = asciiLower(s.name);
        if (s.value) t.append_attribute(key.c_str()) = st::printExpr(*s.value).c_str();
      }
      for (const auto& prog : res.programs) {
        if (prog.taskName.empty() || prog.taskName != task.name) continue;
        pugi::xml_node inst = t.append_child("pouInstance");
        inst.append_attribute("name") = prog.instanceName.c_str();
        inst.append_attribute("typeName") = prog.typeName.c_str();
      }
    }
    for (const auto& block : res.globals) varList(r, block, "globalVars");
    for (const auto& prog : res.programs) {
      if (!prog.args.empty()) unsupported(prog.loc, "arguments of a PROGRAM instance");
      bool inTask = false;
      for (const auto& task : res.tasks) inTask = inTask || task.name == prog.taskName;
      if (inTask) continue;
      if (!prog.taskName.empty()) diags_.error(diag::X004, prog.loc, "unknown TASK '" + prog.taskName + "'");
      pugi::xml_node inst = r.append_child("pouInstance");
      inst.append_attribute("name") = prog.instanceName.c_str();
      inst.append_attribute("typeName") = prog.typeName.c_str();
    }
  }
  for (const auto& block : cfg.globals) varList(c, block, "globalVars");
}

std::string Exporter::run(const std::vector<const st::CompilationUnit*>& units) {
  size_t errorsBefore = diags_.errorCount();
  pugi::xml_document doc;
  pugi::xml_node project = doc.append_child("project");
  project.append_attribute("xmlns") = "http://www.plcopen.org/xml/tc6_0201";
  project.append_attribute("xmlns:xhtml") = "http://www.w3.org/1999/xhtml";
  pugi::xml_node header = project.append_child("fileHeader");
  header.append_attribute("companyName") = "";
  header.append_attribute("productName") = "virtcom";
  header.append_attribute("productVersion") = "1";
  header.append_attribute("creationDateTime") = options_.timestamp.c_str();
  pugi::xml_node content = project.append_child("contentHeader");
  content.append_attribute("name") = options_.projectName.c_str();
  content.append_attribute("modificationDateTime") = options_.timestamp.c_str();
  pugi::xml_node coordinates = content.append_child("coordinateInfo");
  for (const char* language : {"fbd", "ld", "sfc"}) {
    pugi::xml_node scaling = coordinates.append_child(language).append_child("scaling");
    scaling.append_attribute("x") = "1";
    scaling.append_attribute("y") = "1";
  }
  pugi::xml_node types = project.append_child("types");
  pugi::xml_node dataTypes = types.append_child("dataTypes");
  pugi::xml_node pous = types.append_child("pous");
  pugi::xml_node configurations = project.append_child("instances").append_child("configurations");
  pugi::xml_node addData;
  for (const st::CompilationUnit* unit : units) {
    for (const auto& iface : unit->interfaces) unsupported(iface.loc, "INTERFACE '" + iface.name + "'");
    for (const auto& t : unit->types) {
      pugi::xml_node d = dataTypes.append_child("dataType");
      d.append_attribute("name") = t.name.c_str();
      type(d.append_child("baseType"), t.spec);
      if (t.init) value(d.append_child("initialValue"), *t.init);
      writeAttributes(d, t.attributes);
    }
    for (const auto& p : unit->pous) pou(pous, *p);
    for (const auto& cfg : unit->configurations) configuration(configurations, cfg);
    for (const auto& gvl : unit->globals) {
      if (!addData) addData = project.append_child("addData");
      pugi::xml_node data = addData.append_child("data");
      data.append_attribute("name") = kGlobalVarsData;
      data.append_attribute("handleUnknown") = "implementation";
      for (const auto& block : gvl.blocks) {
        pugi::xml_node list = data.append_child("globalVars");
        list.append_attribute("name") = gvl.name.c_str();
        if (block.constant) list.append_attribute("constant") = "true";
        if (block.retain) list.append_attribute("retain") = "true";
        if (block.persistent) list.append_attribute("persistent") = "true";
        for (const auto& decl : block.vars) variable(list, decl);
        if (&block == &gvl.blocks.front()) writeAttributes(list, gvl.attributes);
      }
    }
  }
  if (diags_.errorCount() != errorsBefore) return {};
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

}  // namespace

void detail::writeStText(pugi::xml_node language, const std::string& text) {
  pugi::xml_node p = language.append_child("xhtml:p");
  // A CDATA section cannot hold "]]>"; such text goes escaped instead.
  p.append_child(text.find("]]>") == std::string::npos ? pugi::node_cdata : pugi::node_pcdata).set_value(text.c_str());
}

std::string exportProject(const std::vector<const st::CompilationUnit*>& units, const ExportOptions& options,
                          Diagnostics& diags) {
  return Exporter(options, diags).run(units);
}

}  // namespace virtcom::plcopen
