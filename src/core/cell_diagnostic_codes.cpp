#include "core/cell_diagnostic_codes.hpp"

#include "core/code_titles.hpp"

namespace virtcom {

namespace {
constexpr CodeTitle kCodeTitles[] = {
#define X(code, title) {#code, title},
#include "core/cell_diagnostic_codes.def"
#undef X
};
}  // namespace

std::string_view cellDiagnosticTitle(std::string_view code) { return codeTitle(kCodeTitles, code); }

}  // namespace virtcom
