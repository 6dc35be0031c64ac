#pragma once
#include <string_view>

namespace virtcom::st {

// One constant per code in diagnostic_codes.def, e.g. diag::E006 == "E006".
namespace diag {
#define X(code, title) inline constexpr std::string_view code = #code;
#include "lang/syntax/diagnostic_codes.def"
#undef X
}  // namespace diag

// The short title of a code ("unexpected token"), or empty if unknown.
std::string_view diagnosticTitle(std::string_view code);

}  // namespace virtcom::st
