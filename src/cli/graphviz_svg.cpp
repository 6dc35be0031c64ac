#include "cli/graphviz_svg.hpp"

#include <graphviz/gvc.h>

#include <memory>

// The plugin tables of the two Graphviz plugins used, linked in rather than found through
// Graphviz's plugin configuration file at run time (which may be missing).
extern "C" {
extern gvplugin_library_t gvplugin_dot_layout_LTX_library;
extern gvplugin_library_t gvplugin_core_LTX_library;
}

// Graphviz 2.42's dot layout leaks the virtual nodes and edges it makes for clusters (inside the
// plugin, after gvFreeLayout and agclose); nothing the API offers frees them. The sanitizer build
// reads this hook (LeakSanitizer's default suppressions) so those leaks do not fail the e2e tests.
// With the fast unwinder a Graphviz stack often ends in libgvc's own allocator (gmalloc), so
// both libraries are named; our code never allocates through them, so our allocations stay
// checked. Unused without LeakSanitizer.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgvc.so\nleak:libgvplugin_dot_layout.so\n";
}

namespace virtcom::cli {

namespace {

lt_symlist_t kPlugins[] = {
    {"gvplugin_dot_layout_LTX_library", &gvplugin_dot_layout_LTX_library},
    {"gvplugin_core_LTX_library", &gvplugin_core_LTX_library},
    {nullptr, nullptr},
};

struct ContextDeleter {
  void operator()(GVC_t* gvc) const { gvFreeContext(gvc); }
};
struct GraphDeleter {
  void operator()(Agraph_t* g) const { agclose(g); }
};

}  // namespace

std::optional<std::string> renderSvg(const std::string& dot) {
  std::unique_ptr<GVC_t, ContextDeleter> gvc(gvContextPlugins(kPlugins, 0));
  if (!gvc) return std::nullopt;
  std::unique_ptr<Agraph_t, GraphDeleter> graph(agmemread(dot.c_str()));
  if (!graph) return std::nullopt;
  if (gvLayout(gvc.get(), graph.get(), "dot") != 0) return std::nullopt;
  char* data = nullptr;
  unsigned int length = 0;
  const int rc = gvRenderData(gvc.get(), graph.get(), "svg", &data, &length);
  std::optional<std::string> svg;
  if (rc == 0 && data) svg = std::string(data, length);
  gvFreeRenderData(data);
  gvFreeLayout(gvc.get(), graph.get());
  return svg;
}

}  // namespace virtcom::cli
