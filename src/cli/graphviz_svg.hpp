#pragma once
// Graphviz (Debian libgraphviz-dev: libgvc, libcgraph) behind one function, so that only
// `virtcom ad render` loads it: the calls into Graphviz are in the module virtcom-graphviz.so
// (graphviz_module.cpp), built beside the executable and loaded on the first call, so the other
// commands start without Graphviz's eight libraries (core/bundled_module.hpp).
#include <expected>
#include <string>

namespace virtcom::cli {

// The SVG of `dot` laid out by Graphviz's dot engine. Only the dot layout and the core
// renderers are loaded (no text-layout plugin), so text widths are Graphviz's own estimates and
// the output does not depend on the fonts installed. Error text if the module cannot be loaded,
// or if Graphviz rejects the text or the layout fails (Graphviz prints its reason on stderr).
// Allocates; not thread-safe (Graphviz keeps global state).
std::expected<std::string, std::string> renderSvg(const std::string& dot);

// The module's one function (extern "C", so that it is found by name): the SVG of `dot` into
// `svg`; false if Graphviz rejects the text or the layout fails.
using RenderSvgFunction = bool (*)(const char* dot, std::string* svg);
inline constexpr const char* kGraphvizModule = "virtcom-graphviz.so";
inline constexpr const char* kRenderSvgSymbol = "virtcomRenderSvg";

}  // namespace virtcom::cli
