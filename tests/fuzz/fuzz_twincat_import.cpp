// libFuzzer target: any bytes must read as a TwinCAT source file (and compile when clean) without
// crashing, hanging or leaking, and every diagnostic must render (its location must point into
// the input).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/plcopen/twincat_file.hpp"
#include "lang/st/compiler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  const std::vector<virtcom::st::SourceInput> inputs{{"fuzz.TcPOU", text, virtcom::plcopen::importTwinCatFile}};
  (void)virtcom::st::compileProgram(inputs, sources, diags);
  (void)diags.render(sources);
  return 0;
}
