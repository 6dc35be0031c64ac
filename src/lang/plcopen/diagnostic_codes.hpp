#pragma once
#include <string_view>

namespace virtcom::plcopen {

// One constant per code in diagnostic_codes.def, e.g. diag::X003 == "X003".
namespace diag {
#define X(code, title) inline constexpr std::string_view code = #code;
#include "lang/plcopen/diagnostic_codes.def"
#undef X
}  // namespace diag

}  // namespace virtcom::plcopen
