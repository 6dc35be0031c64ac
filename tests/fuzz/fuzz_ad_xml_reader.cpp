// libFuzzer target: any bytes must read as an AD-XML file without crashing, hanging or leaking;
// every diagnostic must render (its location must point into the input); a clean file must
// survive the round trip through the .ad text unchanged (the writers and readers agree),
// decompose, print its tables and compile.
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
#include "lang/ad/writer.hpp"
#include "lang/st/compiler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  uint32_t fileId = sources.addFile("fuzz.adxml", text);
  virtcom::ad::Program program = virtcom::ad::readXmlProgram(fileId, text, diags);
  (void)diags.render(sources);
  if (diags.hasErrors()) return 0;
  std::string normalised = virtcom::ad::formatText(program);
  virtcom::Diagnostics textDiags;
  virtcom::ad::Program again = virtcom::ad::readProgram(0, normalised, textDiags);
  if (textDiags.hasErrors() || virtcom::ad::formatXml(again) != virtcom::ad::formatXml(program)) __builtin_trap();
  std::vector<virtcom::ad::DiagramTables> tables;
  for (const virtcom::ad::Diagram& d : program.diagrams) tables.push_back(virtcom::ad::decompose(d));
  (void)virtcom::ad::formatTables(program, tables, virtcom::ad::TableFormat::Csv);
  virtcom::SourceManager compileSources;
  virtcom::Diagnostics compileDiags;
  const std::vector<virtcom::st::SourceInput> inputs{{"fuzz.adxml", text, virtcom::ad::importXmlDiagrams}};
  (void)virtcom::st::compileProgram(inputs, compileSources, compileDiags);
  (void)compileDiags.render(compileSources);
  return 0;
}
