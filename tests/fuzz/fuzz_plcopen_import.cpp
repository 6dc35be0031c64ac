// libFuzzer target: any bytes must import as PLCopen XML (and, when the import is clean, compile
// and export again, charts as graphical SFC) without crashing, hanging or leaking, and every
// diagnostic must render (its location must point into the input).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/plcopen/exporter.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compiler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  const std::vector<virtcom::st::SourceInput> inputs{{"fuzz.xml", text, virtcom::plcopen::importProject}};
  auto module = virtcom::st::compileProgram(inputs, sources, diags);
  (void)diags.render(sources);
  if (!module) return 0;
  virtcom::SourceManager exportSources;
  virtcom::Diagnostics exportDiags;
  virtcom::st::NodeId next = 0;
  auto units = virtcom::st::parseInputs(inputs, exportSources, exportDiags, next);
  std::vector<const virtcom::st::CompilationUnit*> pointers;
  for (const auto& u : units) pointers.push_back(&u);
  (void)virtcom::plcopen::exportProject(pointers, {}, exportDiags);
  (void)exportDiags.render(exportSources);
  return 0;
}
