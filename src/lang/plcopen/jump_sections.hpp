#pragma once
// Bodies with labels and jumps (LD/FBD networks, IL) in ST, which has no GOTO: the statements
// are cut into sections at the labels and run as
//   jump := 0; WHILE TRUE DO IF jump <= 0 THEN <section 0> END_IF; ... EXIT; END_WHILE
// A jump to the label opening section k is `jump := k; CONTINUE;`: a forward jump skips the
// sections before k, a backward jump loops (the watchdog catches an endless one).
#include <string>
#include <vector>

#include "lang/plcopen/ast_builder.hpp"

namespace virtcom::plcopen::detail {

// `jump := section; CONTINUE;`
st::StmtList jumpToSection(AstBuilder& b, const std::string& jumpVar, size_t section, SourceLocation loc);

// The sections as one statement list; without a jump variable (no jump taken anywhere) they are
// simply concatenated.
st::StmtList joinSections(AstBuilder& b, std::vector<st::StmtList> sections, const std::string& jumpVar,
                          SourceLocation loc);

}  // namespace virtcom::plcopen::detail
