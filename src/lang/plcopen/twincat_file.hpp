#pragma once
// TwinCAT 3 source files: a TwinCAT PLC project keeps each POU, interface, data type and global
// variable list in its own XML file (.TcPOU, .TcIO, .TcDUT, .TcGVL) whose ST text sits in CDATA
// sections: the declaration, the body, and one element per METHOD, PROPERTY accessor and ACTION.
// They are read as the Structured Text they contain, so diagnostics point into the XML file at
// the line and column of the ST text.
#include <cstdint>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::plcopen {

// Has the signature of st::FrontEnd. Never throws: malformed XML (X001), a file that is not a
// TwinCAT source file (X002), missing parts (X003) and bodies in a language other than ST
// (X004) are diagnostics; the ST parser reports the ST.
st::CompilationUnit importTwinCatFile(uint32_t fileId, std::string_view text, Diagnostics& diags,
                                      st::NodeId& nextNodeId);

// True for .TcPOU, .TcIO, .TcDUT, .TcGVL and .TcTTO (a task: warned about, not read), any case.
bool isTwinCatPath(std::string_view path);

}  // namespace virtcom::plcopen
