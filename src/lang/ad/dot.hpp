#pragma once
// The drawing of activity diagrams (seed 002, Figure 3) as Graphviz DOT text, laid out top to
// bottom by the dot engine (`virtcom ad render`): start a filled circle, stop a bull's-eye,
// activities rounded boxes with their signal and its port kind (I/O/M), timers and counters
// boxes with block type and preset, AND-join/AND-split black bars, OR-join a diamond (UML's
// merge), arcs with arrowheads, the NOT bar (`tee`) at the source end of a NOT-IN arc and at the
// target end of a NOT-OUT arc. Pure text, no Graphviz library: the layout is the caller's.
#include <string>
#include <vector>

#include "lang/ad/diagram.hpp"

namespace virtcom::ad {

// One graph holding `diagrams` (pointers into `program`), one cluster each, side by side in
// the given order. Every node's DOT `id` (and so its SVG element id) is `Diagram.ElementId`,
// every arc's `Diagram.arcN` (N: 1-based, in written order), every cluster's the diagram name.
// Deterministic: the same program gives the same text. Allocates; never fails.
std::string toDot(const Program& program, const std::vector<const Diagram*>& diagrams);

}  // namespace virtcom::ad
