#pragma once
#include <string_view>

namespace virtcom::st {
// The IEC standard function blocks, written in ST and compiled with every program (timers use
// the task clock through __SYSTIME_NS, so they run in virtual time).
std::string_view standardLibrarySource();
// The name the standard library's source is registered under (diagnostics, the file table).
inline constexpr std::string_view kStandardLibraryPath = "<standard library>";
}  // namespace virtcom::st
