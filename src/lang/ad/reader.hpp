#pragma once
// The two forms of an activity-diagram file (docs/activity-diagrams.md): the hand-written text
// (.ad: one element or arc per line, so a change to a diagram is a change to the lines it
// touches) and AD-XML (.adxml: the same model as XML elements, for tools).
#include <cstdint>
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/ad/diagram.hpp"

namespace virtcom::ad {

// Reads a whole .ad file and checks it (checkProgram). Every mistake becomes a diagnostic
// (A0xx) at its file:line:col; what could be read is returned, so a caller must look at `diags`
// before using the program. Never throws on bad input; allocates the model.
Program readProgram(uint32_t fileId, std::string_view text, Diagnostics& diags);

// The structural rules a diagram must keep to be decomposed (dangling or one-branch bars, NOT
// arcs at the wrong end, start activities, written inputs, twice-driven block inputs, cycles
// without memory). Reports A005-A011; called by readProgram.
void checkProgram(const Program& program, Diagnostics& diags);

// True for the files readProgram() reads: the extension is .ad (any case).
bool isDiagramPath(std::string_view path);

// Reads and checks an AD-XML file (docs/activity-diagrams.md, "AD-XML"): the same model as
// the text form, element for element, with the same checks and A0xx codes at the XML element's
// (or attribute's) line:col; a document that is not well-formed XML or not a <program> is A014.
// Never throws on bad input; allocates the model.
Program readXmlProgram(uint32_t fileId, std::string_view text, Diagnostics& diags);

// True for the files readXmlProgram() reads: the extension is .adxml (any case).
bool isXmlDiagramPath(std::string_view path);

// readXmlProgram for .adxml paths, readProgram for any other.
Program readProgramFile(uint32_t fileId, std::string_view path, std::string_view text, Diagnostics& diags);

}  // namespace virtcom::ad
