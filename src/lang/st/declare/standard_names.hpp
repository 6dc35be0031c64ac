#pragma once
#include <string_view>

namespace virtcom::st {
// True for the names of IEC standard functions (ADD, SEL, LIMIT, REAL_TO_INT, ...), which
// cannot be used as variable names (IEC 61131-3; CODESYS rejects them too).
bool isStandardFunctionName(std::string_view upperName);
}  // namespace virtcom::st
