// libFuzzer target: any bytes must import as PLCopen XML (and, when the import is clean, compile)
// without crashing, hanging or leaking, and every diagnostic must render (its location must
// point into the input).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compiler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  auto module = virtcom::st::compileProgram({{"fuzz.xml", text, virtcom::plcopen::importProject}}, sources, diags);
  (void)module;
  (void)diags.render(sources);
  return 0;
}
