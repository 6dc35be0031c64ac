// libFuzzer target: any bytes must lex and parse without crashing, hanging or leaking, and every
// diagnostic must render (its location must point into the input).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/parse/lexer.hpp"
#include "lang/st/parse/parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::Diagnostics lexDiags;
  virtcom::st::lex(0, text, lexDiags);
  virtcom::SourceManager sources;
  uint32_t fileId = sources.addFile("fuzz.st", text);
  virtcom::Diagnostics diags;
  virtcom::st::NodeId nextNodeId = 0;
  virtcom::st::parseFile(fileId, text, diags, nextNodeId);
  (void)diags.render(sources);
  return 0;
}
