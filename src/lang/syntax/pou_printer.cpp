// Whole POUs as ST text (printer.hpp): declarations around the statement printer.
#include <string>

#include "lang/syntax/printer.hpp"

namespace virtcom::st {

namespace {

const char* sectionKeyword(VarSection section) {
  switch (section) {
    case VarSection::Var: return "VAR";
    case VarSection::Input: return "VAR_INPUT";
    case VarSection::Output: return "VAR_OUTPUT";
    case VarSection::InOut: return "VAR_IN_OUT";
    case VarSection::Temp: return "VAR_TEMP";
    case VarSection::Global: return "VAR_GLOBAL";
    case VarSection::External: return "VAR_EXTERNAL";
    case VarSection::Inst: return "VAR_INST";
    case VarSection::Stat: return "VAR_STAT";
  }
  return "VAR";
}

const char* pouKeyword(PouKind kind) {
  switch (kind) {
    case PouKind::Program: return "PROGRAM";
    case PouKind::Function: return "FUNCTION";
    case PouKind::FunctionBlock: return "FUNCTION_BLOCK";
    case PouKind::Method: return "METHOD";
    case PouKind::Action: return "ACTION";
    case PouKind::PropertyGet: case PouKind::PropertySet: return "PROPERTY";
  }
  return "PROGRAM";
}

void printVarBlock(const VarBlock& block, std::string& out) {
  out += sectionKeyword(block.section);
  if (block.constant) out += " CONSTANT";
  if (block.retain) out += " RETAIN";
  if (block.persistent) out += " PERSISTENT";
  out += '\n';
  for (const VarDecl& v : block.vars) {
    for (const Attribute& a : v.attributes)
      out += "\t{attribute '" + a.name + "'" + (a.value.empty() ? "" : " := '" + a.value + "'") + "}\n";
    std::string names;
    for (const DeclName& n : v.names) names += (names.empty() ? "" : ", ") + n.name;
    out += '\t' + names;
    if (!v.location.empty()) out += " AT " + v.location;
    out += " : " + printType(v.type);
    if (v.edge != EdgeKind::None) out += v.edge == EdgeKind::Rising ? " R_EDGE" : " F_EDGE";
    if (v.init) out += " := " + printExpr(*v.init);
    out += ";\n";
  }
  out += "END_VAR\n";
}

}  // namespace

std::string printType(const TypeSpec& type) {
  auto element = [&] { return type.element ? printType(*type.element) : std::string("?"); };
  switch (type.kind) {
    case TypeSpecKind::Named: return type.name;
    case TypeSpecKind::String: {
      std::string text = type.wide ? "WSTRING" : "STRING";
      return type.length ? text + "(" + printExpr(*type.length) + ")" : text;
    }
    case TypeSpecKind::Array: {
      std::string dims;
      for (const ArrayRange& r : type.dims)
        dims += (dims.empty() ? "" : ", ") + (r.lo ? printExpr(*r.lo) + ".." + printExpr(*r.hi) : std::string("*"));
      return "ARRAY [" + dims + "] OF " + element();
    }
    case TypeSpecKind::Pointer: return "POINTER TO " + element();
    case TypeSpecKind::Reference: return "REFERENCE TO " + element();
    case TypeSpecKind::Subrange: return element() + " (" + printExpr(*type.lo) + ".." + printExpr(*type.hi) + ")";
    case TypeSpecKind::Enum: {
      std::string values;
      for (const EnumValueDecl& v : type.enumValues)
        values += (values.empty() ? "" : ", ") + v.name + (v.value ? " := " + printExpr(*v.value) : std::string());
      return "(" + values + ")" + (type.name.empty() ? "" : " " + type.name);
    }
    case TypeSpecKind::Struct: break;
  }
  std::string fields = "STRUCT\n";
  for (const VarDecl& f : type.fields)
    for (const DeclName& n : f.names) fields += "\t" + n.name + " : " + printType(f.type) + ";\n";
  return fields + "END_STRUCT";
}

std::string printPou(const Pou& pou) {
  std::string out = std::string(pouKeyword(pou.kind)) + " " + pou.name;
  if (pou.kind == PouKind::Action) out += ':';
  if (pou.hasReturnType) out += " : " + printType(pou.returnType);
  out += '\n';
  for (const VarBlock& block : pou.varBlocks) printVarBlock(block, out);
  for (const auto& action : pou.actions) out += '\n' + printPou(*action);
  if (!pou.actions.empty()) out += '\n';
  out += printStatements(pou.body, 1);
  out += "END_" + std::string(pouKeyword(pou.kind)) + "\n";
  return out;
}

}  // namespace virtcom::st
