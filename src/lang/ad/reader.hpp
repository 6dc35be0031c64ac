#pragma once
// The hand-written text form of activity diagrams (.ad files, docs/activity-diagrams.md): one
// element or arc per line, so a change to a diagram is a change to the lines it touches.
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

}  // namespace virtcom::ad
