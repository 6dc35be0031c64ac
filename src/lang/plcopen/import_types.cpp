// Data types, interfaces, variables and initial values; see import_internal.hpp.
#include <cstring>

#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/import_internal.hpp"

namespace virtcom::plcopen::detail {

namespace {

// Types nest (ARRAY OF ARRAY OF STRUCT ...); a bound keeps hostile files off the stack.
constexpr int kMaxTypeDepth = 32;

bool isElementaryName(std::string_view name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

bool attributeTrue(pugi::xml_node node, const char* name) {
  std::string_view v = node.attribute(name).value();
  return v == "true" || v == "1";
}

}  // namespace

st::ExprPtr Importer::boundExpr(pugi::xml_node element, const char* attribute) {
  if (!element.attribute(attribute)) {
    error(diag::X003, element, describe(element) + " has no '" + attribute + "' attribute");
    return build_.name("", xml_.at(element));
  }
  return expressionAt(element, attribute);
}

st::TypeSpec Importer::typeIn(pugi::xml_node holder, int depth) {
  pugi::xml_node type = firstElement(holder);
  if (!type) {
    error(diag::X003, holder, "<" + std::string(localName(holder)) + "> names no type");
    st::TypeSpec spec;
    spec.loc = xml_.at(holder);
    return spec;
  }
  return typeOf(type, depth + 1);
}

st::TypeSpec Importer::typeOf(pugi::xml_node type, int depth) {
  st::TypeSpec spec;
  spec.loc = xml_.at(type);
  std::string_view kind = localName(type);
  if (depth > kMaxTypeDepth) {
    error(diag::X004, type, "type nested more than " + std::to_string(kMaxTypeDepth) + " levels deep");
    return spec;
  }
  if (isElementaryName(kind)) {
    spec.name = std::string(kind);  // BOOL, INT, TIME, ...: the checker resolves (and rejects) names
  } else if (kind == "derived") {
    spec.name = type.attribute("name").value();
    if (spec.name.empty()) error(diag::X003, type, "<derived> has no 'name' attribute");
  } else if (kind == "string" || kind == "wstring") {
    spec.kind = st::TypeSpecKind::String;
    spec.wide = kind == "wstring";
    if (type.attribute("length")) spec.length = expressionAt(type, "length");
  } else if (kind == "array") {
    spec.kind = st::TypeSpecKind::Array;
    for (pugi::xml_node dim : children(type, "dimension"))
      spec.dims.push_back({boundExpr(dim, "lower"), boundExpr(dim, "upper")});
    if (spec.dims.empty()) error(diag::X003, type, "<array> has no <dimension>");
    spec.element = std::make_unique<st::TypeSpec>(typeIn(child(type, "baseType"), depth));
  } else if (kind == "pointer") {
    spec.kind = st::TypeSpecKind::Pointer;
    spec.element = std::make_unique<st::TypeSpec>(typeIn(child(type, "baseType"), depth));
  } else if (kind == "subrangeSigned" || kind == "subrangeUnsigned") {
    spec.kind = st::TypeSpecKind::Subrange;
    pugi::xml_node range = child(type, "range");
    spec.lo = boundExpr(range ? range : type, "lower");
    spec.hi = boundExpr(range ? range : type, "upper");
    spec.element = std::make_unique<st::TypeSpec>(typeIn(child(type, "baseType"), depth));
  } else if (kind == "enum") {
    spec.kind = st::TypeSpecKind::Enum;
    for (pugi::xml_node v : children(child(type, "values"), "value")) {
      st::EnumValueDecl ev;
      ev.name = v.attribute("name").value();
      ev.loc = xml_.at(v);
      if (ev.name.empty()) error(diag::X003, v, "enumeration <value> has no 'name' attribute");
      if (v.attribute("value")) ev.value = expressionAt(v, "value");
      spec.enumValues.push_back(std::move(ev));
    }
    if (pugi::xml_node base = firstElement(child(type, "baseType"))) spec.name = typeOf(base, depth + 1).name;
  } else if (kind == "struct") {
    spec.kind = st::TypeSpecKind::Struct;
    for (pugi::xml_node v : children(type, "variable")) spec.fields.push_back(variable(v));
  } else {
    unsupported(type, "type <" + std::string(kind) + ">");
  }
  return spec;
}

st::TypeDecl Importer::importDataType(pugi::xml_node dataType) {
  st::TypeDecl decl;
  decl.name = dataType.attribute("name").value();
  decl.loc = xml_.at(dataType, "name");
  if (decl.name.empty()) error(diag::X003, dataType, "<dataType> has no 'name' attribute");
  decl.spec = typeIn(child(dataType, "baseType"));
  if (std::string base = inheritanceIn(dataType).extends; !base.empty()) {
    if (decl.spec.kind == st::TypeSpecKind::Struct) decl.spec.name = std::move(base);  // STRUCT EXTENDS base
    else unsupported(dataType, "EXTENDS on a type that is not a STRUCT");
  }
  if (pugi::xml_node init = child(dataType, "initialValue")) decl.init = initialValue(init);
  decl.attributes = attributesIn(dataType);
  return decl;
}

void Importer::importInterface(pugi::xml_node interface, st::Pou& pou) {
  static constexpr struct {
    const char* element;
    st::VarSection section;
  } kLists[] = {
      {"inputVars", st::VarSection::Input},     {"outputVars", st::VarSection::Output},
      {"inOutVars", st::VarSection::InOut},     {"localVars", st::VarSection::Var},
      {"tempVars", st::VarSection::Temp},       {"externalVars", st::VarSection::External},
      {"globalVars", st::VarSection::Global},
  };
  for (pugi::xml_node list = interface.first_child(); list; list = list.next_sibling()) {
    if (list.type() != pugi::node_element) continue;
    std::string_view name = localName(list);
    if (name == "returnType") {
      pou.hasReturnType = true;
      pou.returnType = typeIn(list);
      continue;
    }
    if (name == "addData" || name == "documentation") continue;
    bool known = false;
    for (const auto& entry : kLists)
      if (name == entry.element) {
        pou.varBlocks.push_back(varList(list, entry.section));
        known = true;
      }
    if (!known) unsupported(list, "interface section <" + std::string(name) + ">");
  }
}

st::VarBlock Importer::varList(pugi::xml_node list, st::VarSection section) {
  st::VarBlock block;
  block.section = section;
  block.loc = xml_.at(list);
  block.constant = attributeTrue(list, "constant");
  block.retain = attributeTrue(list, "retain");
  block.persistent = attributeTrue(list, "persistent");
  for (pugi::xml_node v : children(list, "variable")) block.vars.push_back(variable(v));
  return block;
}

st::VarDecl Importer::variable(pugi::xml_node v) {
  st::VarDecl decl;
  decl.loc = xml_.at(v, "name");
  std::string name = v.attribute("name").value();
  if (name.empty()) error(diag::X003, v, "<variable> has no 'name' attribute");
  decl.names.push_back({name, decl.loc});
  decl.location = v.attribute("address").value();
  decl.type = typeIn(child(v, "type"));
  if (pugi::xml_node init = child(v, "initialValue")) decl.init = initialValue(init);
  decl.attributes = attributesIn(v);
  return decl;
}

st::ExprPtr Importer::initialValue(pugi::xml_node init) {
  pugi::xml_node v = firstElement(init);
  if (!v) {
    error(diag::X003, init, "<initialValue> holds no value");
    return build_.name("", xml_.at(init));
  }
  return value(v, 0);
}

// <simpleValue value="..."/>, <arrayValue><value repetitionValue="n">...</value></arrayValue>,
// <structValue><value member="m">...</value></structValue>.
st::ExprPtr Importer::value(pugi::xml_node v, int depth) {
  std::string_view kind = localName(v);
  if (depth > kMaxTypeDepth) {
    error(diag::X004, v, "initial value nested more than " + std::to_string(kMaxTypeDepth) + " levels deep");
    return build_.name("", xml_.at(v));
  }
  if (kind == "simpleValue") {
    if (!v.attribute("value")) {
      error(diag::X003, v, "<simpleValue> has no 'value' attribute");
      return build_.name("", xml_.at(v));
    }
    return expressionAt(v, "value");
  }
  bool isArray = kind == "arrayValue";
  if (!isArray && kind != "structValue") {
    unsupported(v, "initial value <" + std::string(kind) + ">");
    return build_.name("", xml_.at(v));
  }
  st::ExprPtr out = build_.expr(isArray ? st::ExprKind::ArrayInit : st::ExprKind::StructInit, xml_.at(v));
  for (pugi::xml_node item : children(v, "value")) {
    pugi::xml_node inner = firstElement(item);
    st::ExprPtr itemValue = inner ? value(inner, depth + 1) : build_.name("", xml_.at(item));
    if (!inner) error(diag::X003, item, "<value> holds no value");
    if (!isArray) {
      st::CallArg arg;
      arg.name = item.attribute("member").value();
      arg.loc = xml_.at(item, "member");
      if (arg.name.empty()) error(diag::X003, item, "structure <value> has no 'member' attribute");
      arg.value = std::move(itemValue);
      out->args.push_back(std::move(arg));
    } else if (pugi::xml_attribute repeat = item.attribute("repetitionValue")) {
      st::ExprPtr r = build_.expr(st::ExprKind::Repeat, xml_.at(item, "repetitionValue"));
      char* end = nullptr;
      r->intValue = std::strtoull(repeat.value(), &end, 10);
      if (end == repeat.value() || *end != '\0')
        error(diag::X005, item, std::string("repetitionValue '") + repeat.value() + "' is not a whole number");
      r->lhs = std::move(itemValue);
      out->items.push_back(std::move(r));
    } else {
      out->items.push_back(std::move(itemValue));
    }
  }
  return out;
}

}  // namespace virtcom::plcopen::detail
