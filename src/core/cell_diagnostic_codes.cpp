#include "core/cell_diagnostic_codes.hpp"

namespace virtcom {

namespace {
struct CodeTitle {
  std::string_view code;
  std::string_view title;
};

constexpr CodeTitle kCodeTitles[] = {
#define X(code, title) {#code, title},
#include "core/cell_diagnostic_codes.def"
#undef X
};
}  // namespace

std::string_view cellDiagnosticTitle(std::string_view code) {
  for (const CodeTitle& entry : kCodeTitles)
    if (entry.code == code) return entry.title;
  return {};
}

}  // namespace virtcom
