#pragma once
// The exit status of the `virtcom` command, one enumerator per row of exit_codes.def.

namespace virtcom::cli {

enum class ExitCode : int {
#define X(name, value, meaning) name = value,
#include "cli/exit_codes.def"
#undef X
};

}  // namespace virtcom::cli
