#pragma once
// Internal to the TC6 writer: pieces shared by exporter.cpp and export_sfc.cpp.
#include <pugixml.hpp>

#include <string>

#include "lang/sfc/sfc_model.hpp"

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

}  // namespace virtcom::plcopen::detail
