#pragma once
// The PLCopen TC6 XML 2.01 exporter: parsed programs (ST files, imported XML) to one project
// file that vendor tools (CODESYS, TwinCAT, Beremiz) open, and that importProject() reads back
// into the same program.
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::plcopen {

struct ExportOptions {
  std::string projectName = "virtcom";
  std::string timestamp = "1970-01-01T00:00:00";  // fileHeader creationDateTime / modificationDateTime
};

// Writes the units as one project: TYPEs as <dataTypes>; POUs with structured interfaces and ST
// bodies (in CDATA), charts (textual or imported SFC, st::Pou::chart) as graphical <SFC> bodies
// without their lowered ST, ACTIONs as <actions>; METHODs and global variable lists as the CODESYS
// vendor data (`.../plcopenxml/method`, `.../plcopenxml/globalvars`) CODESYS and this importer
// read; CONFIGURATIONs as <instances>. What TC6 cannot hold (INTERFACE, PROPERTY, EXTENDS,
// REFERENCE TO, ARRAY[*], VAR_INST/VAR_STAT, FB_init arguments) is reported as X004 at the
// construct; attribute pragmas go into CODESYS `.../plcopenxml/attributes` data. Returns the XML text, or an
// empty string if there was an error. Never throws.
std::string exportProject(const std::vector<const st::CompilationUnit*>& units, const ExportOptions& options,
                          Diagnostics& diags);

}  // namespace virtcom::plcopen
