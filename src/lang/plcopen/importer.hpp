#pragma once
// The PLCopen TC6 XML importer: a project file (TC6 2.01 or 2.00, as written by CODESYS, TwinCAT,
// Beremiz or the OpenPLC editor) to the same syntax tree the ST parser produces, so the checker,
// code generator and everything downstream work unchanged.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/syntax/ast.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::plcopen {

// Imports data types, POUs with their interfaces and bodies (ST parsed in place; LD and FBD
// translated to ST statements in the standard's execution order; SFC charts), global variable
// lists (configuration/resource globals and CODESYS `globalvars` vendor data) and
// configurations/resources/tasks/program instances. Has the signature of st::FrontEnd.
// Never throws: malformed XML and unsupported constructs become diagnostics (X0xx, plus the ST
// parser's E0xx for embedded ST) located at the XML element (and naming its localId); what
// could be imported is returned. Every node gets a fresh id from `nextNodeId`.
st::CompilationUnit importProject(uint32_t fileId, std::string_view text, Diagnostics& diags, st::NodeId& nextNodeId);

// True for the files importProject() reads: the extension is .xml (any case).
bool isPlcopenPath(std::string_view path);

// A compiler input for a file of any kind: .xml files get importProject() as front end,
// TwinCAT source files (.TcPOU, .TcIO, .TcDUT, .TcGVL) importTwinCatFile(), activity diagrams
// (.ad) ad::importDiagrams(), all others are Structured Text. Every command and the cell loader pick front ends only here.
st::SourceInput sourceInput(std::string path, std::string text);

}  // namespace virtcom::plcopen
