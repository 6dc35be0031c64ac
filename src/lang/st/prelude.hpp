#pragma once
#include <string_view>

namespace virtcom::st {
// The IEC standard function blocks, written in ST and compiled with every program (timers use
// the task clock through __SYSTIME_NS, so they run in virtual time).
std::string_view standardLibrarySource();
}  // namespace virtcom::st
