// The module virtcom-graphviz.so: the calls into Graphviz, loaded by renderSvg() (graphviz_svg.cpp)
// only when `virtcom ad render` draws. It links Graphviz and nothing of virtcom but this header.
#include "cli/graphviz_svg.hpp"

#include <graphviz/gvc.h>

#include <memory>
#include <type_traits>

// The plugin tables of the two Graphviz plugins used, linked in rather than found through
// Graphviz's plugin configuration file at run time (which may be missing).
extern "C" {
extern gvplugin_library_t gvplugin_dot_layout_LTX_library;
extern gvplugin_library_t gvplugin_core_LTX_library;
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

bool renderSvgWithGraphviz(const char* dot, std::string& svg) {
  std::unique_ptr<GVC_t, ContextDeleter> gvc(gvContextPlugins(kPlugins, 0));
  if (!gvc) return false;
  std::unique_ptr<Agraph_t, GraphDeleter> graph(agmemread(dot));
  if (!graph) return false;
  if (gvLayout(gvc.get(), graph.get(), "dot") != 0) return false;
  char* data = nullptr;
  unsigned int length = 0;
  const int rc = gvRenderData(gvc.get(), graph.get(), "svg", &data, &length);
  const bool ok = rc == 0 && data;
  if (ok) svg.assign(data, length);
  gvFreeRenderData(data);
  gvFreeLayout(gvc.get(), graph.get());
  return ok;
}

}  // namespace

}  // namespace virtcom::cli

extern "C" [[gnu::visibility("default")]] bool virtcomRenderSvg(const char* dot, std::string* svg) {
  static_assert(std::is_same_v<decltype(&virtcomRenderSvg), virtcom::cli::RenderSvgFunction>);
  return virtcom::cli::renderSvgWithGraphviz(dot, *svg);
}
