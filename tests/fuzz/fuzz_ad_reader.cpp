// libFuzzer target: any bytes must read as an activity-diagram file without crashing, hanging
// or leaking; a clean file must decompose, print its tables and compile; every diagnostic must
// render (its location must point into the input).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/ad/decompose.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/tables.hpp"
#include "lang/st/compiler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  uint32_t fileId = sources.addFile("fuzz.ad", text);
  virtcom::ad::Program program = virtcom::ad::readProgram(fileId, text, diags);
  (void)diags.render(sources);
  if (diags.hasErrors()) return 0;
  std::vector<virtcom::ad::DiagramTables> tables;
  for (const virtcom::ad::Diagram& d : program.diagrams) tables.push_back(virtcom::ad::decompose(d));
  (void)virtcom::ad::formatTables(program, tables, virtcom::ad::TableFormat::Csv);
  virtcom::SourceManager compileSources;
  virtcom::Diagnostics compileDiags;
  const std::vector<virtcom::st::SourceInput> inputs{{"fuzz.ad", text, virtcom::ad::importDiagrams}};
  (void)virtcom::st::compileProgram(inputs, compileSources, compileDiags);
  (void)compileDiags.render(compileSources);
  return 0;
}
