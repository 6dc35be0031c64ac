#include "cli/graphviz_svg.hpp"

#include "core/bundled_module.hpp"

// Graphviz 2.42's dot layout leaks the virtual nodes and edges it makes for clusters (inside the
// plugin, after gvFreeLayout and agclose); nothing the API offers frees them. The sanitizer build
// reads this hook (LeakSanitizer's default suppressions, looked up in the executable) so those
// leaks do not fail the e2e tests. With the fast unwinder a Graphviz stack often ends in libgvc's
// own allocator (gmalloc), so both libraries are named; our code never allocates through them,
// so our allocations stay checked. Unused without LeakSanitizer.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgvc.so\nleak:libgvplugin_dot_layout.so\n";
}

namespace virtcom::cli {

std::expected<std::string, std::string> renderSvg(const std::string& dot) {
  auto render = bundledModuleSymbol(kGraphvizModule, kRenderSvgSymbol);
  if (!render) return std::unexpected(render.error());
  std::string svg;
  if (!reinterpret_cast<RenderSvgFunction>(*render)(dot.c_str(), &svg))
    return std::unexpected("Graphviz could not lay out the diagrams");
  return svg;
}

}  // namespace virtcom::cli
