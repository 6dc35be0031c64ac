#pragma once
// Internal to the TC6 writer: pieces shared by exporter.cpp, export_sfc.cpp and export_ladder.cpp.
#include <pugixml.hpp>

#include <string>

#include "lang/sfc/sfc_model.hpp"
#include "lang/syntax/ladder.hpp"

namespace virtcom::plcopen::detail {

// Fills a language element (<ST>) with the text as its <xhtml:p>, in CDATA unless the text
// holds "]]>" (which a CDATA section cannot).
void writeStText(pugi::xml_node language, const std::string& text);

// The chart's named transitions as the POU's <transitions> (TC6 puts them before the body).
void writeChartTransitions(pugi::xml_node pou, const sfc::Chart& chart);

// The chart as a graphical <SFC> body of `pou`: steps, transitions with ST conditions, action
// blocks (qualifier, duration; references to ACTIONs and BOOL variables, the chart's own actions
// inline), selection and simultaneous divergences and convergences, and a jumpStep for every
// transition into a step declared before (or at) its source, connected by localId/refLocalId.
void writeChartBody(pugi::xml_node pou, const sfc::Chart& chart);

// The rungs as a graphical <LD> body of `parent` (a pou or an action), one after the other:
// per rung an optional comment, a left power rail, the contacts (series = AND, parallel
// branches = OR), the outputs one below the other (coils normal / negated / set / reset, and
// function blocks with the power on one input and a constant inVariable on another) and a right
// power rail, connected by localId/refLocalId (export_ladder.cpp).
void writeLadderBody(pugi::xml_node parent, const st::Ladder& ladder);

}  // namespace virtcom::plcopen::detail
