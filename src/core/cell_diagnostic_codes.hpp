#pragma once
// The codes of cell-file diagnostics (C0xx), one constant per row of cell_diagnostic_codes.def.
// They live in core, below every layer that reports them: core's ConfigReader (C010, C011), the
// device and drive factories, the cell loader and the `virtcom run` command (the ADS bridge).
#include <string_view>

namespace virtcom {

// e.g. celldiag::C010 == "C010"; a Diagnostic keeps the view, so the text is static.
namespace celldiag {
#define X(code, title) inline constexpr std::string_view code = #code;
#include "core/cell_diagnostic_codes.def"
#undef X
}  // namespace celldiag

// The short title of a cell code ("invalid setting"), or empty if unknown.
std::string_view cellDiagnosticTitle(std::string_view code);

}  // namespace virtcom
