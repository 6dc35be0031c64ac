#pragma once
// The model back to a file, in either form (docs/activity-diagrams.md, "AD-XML"): what
// `virtcom ad convert` writes. Reading what these write gives the same model again (up to
// locations), so .ad -> .adxml -> .ad gives the normalised text of the original.
#include <string>

#include "lang/ad/diagram.hpp"

namespace virtcom::ad {

// The normalised .ad text: `program`, the ports, then per diagram its elements in the order
// declared and its arcs in the order written (the rule order), one per line, keywords in lower
// case, two spaces of indentation, single spaces between words, no comments; an activity's
// variable only when it differs from its id; presets as T#1s500ms and decimal counts.
std::string formatText(const Program& program);

// The same model as AD-XML: <program name> holding <port> and <diagram> elements, a diagram
// holding one element per node (named by its keyword) and one <arc from to [kind]> per arc, in
// the same order as formatText. Allocates; never fails.
std::string formatXml(const Program& program);

}  // namespace virtcom::ad
