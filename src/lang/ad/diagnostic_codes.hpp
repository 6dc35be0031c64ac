#pragma once
#include <string_view>

namespace virtcom::ad {

// One constant per code in diagnostic_codes.def, e.g. diag::A004 == "A004".
namespace diag {
#define X(code, title) inline constexpr std::string_view code = #code;
#include "lang/ad/diagnostic_codes.def"
#undef X
}  // namespace diag

}  // namespace virtcom::ad
