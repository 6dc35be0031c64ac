#include "lang/plcopen/jump_sections.hpp"

namespace virtcom::plcopen::detail {

st::StmtList jumpToSection(AstBuilder& b, const std::string& jumpVar, size_t section, SourceLocation loc) {
  st::StmtList out;
  out.push_back(b.assign(b.name(jumpVar, loc), b.intLit(section, loc)));
  out.push_back(b.simple(st::StmtKind::Continue, loc));
  return out;
}

st::StmtList joinSections(AstBuilder& b, std::vector<st::StmtList> sections, const std::string& jumpVar,
                          SourceLocation loc) {
  st::StmtList body;
  if (jumpVar.empty()) {
    for (auto& section : sections)
      for (auto& s : section) body.push_back(std::move(s));
    return body;
  }
  body.push_back(b.assign(b.name(jumpVar, loc), b.intLit(0, loc)));
  st::StmtList loop;
  for (size_t k = 0; k < sections.size(); ++k) {
    st::ExprPtr reached = b.binary(st::BinaryOp::Le, b.name(jumpVar, loc), b.intLit(k, loc));
    loop.push_back(b.ifThen(std::move(reached), std::move(sections[k])));
  }
  loop.push_back(b.simple(st::StmtKind::Exit, loc));
  body.push_back(b.whileLoop(b.boolLit(true, loc), std::move(loop)));
  return body;
}

}  // namespace virtcom::plcopen::detail
