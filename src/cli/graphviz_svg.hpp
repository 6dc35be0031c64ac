#pragma once
// Graphviz (Debian libgraphviz-dev: libgvc, libcgraph) behind one function, so that only `cli`
// links it: DOT text laid out by the dot engine and rendered as SVG.
#include <optional>
#include <string>

namespace virtcom::cli {

// The SVG of `dot` laid out by Graphviz's dot engine. Only the dot layout and the core
// renderers are loaded (no text-layout plugin), so text widths are Graphviz's own estimates and
// the output does not depend on the fonts installed. Nullopt if Graphviz rejects the text or the
// layout fails (Graphviz prints its reason on stderr). Allocates; not thread-safe (Graphviz
// keeps global state).
std::optional<std::string> renderSvg(const std::string& dot);

}  // namespace virtcom::cli
