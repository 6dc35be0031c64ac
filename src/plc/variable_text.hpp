#pragma once
// Writing a variable of the PLC from outside its program (`--set`, the HMI's write and force).
#include <cstdint>
#include <string>
#include <string_view>

#include "bytecode/module.hpp"

namespace virtcom::plc {

// Parses `text` as an IEC literal of the variable's type into `memory`; a located input (%I) is
// also copied into `inputImage` (when given), so that the next scan's input copy keeps it.
// Returns the error text, empty on success. Allocates (string work): not for the scan path.
std::string writeVariableText(const bc::Module& m, const bc::VarRef& ref, std::string_view text, uint8_t* memory,
                              uint8_t* inputImage);

// Copies the variable's bytes from `memory` into `inputImage` if it is a located input (%I);
// nothing otherwise. Allocates nothing (the scan path may call it).
void syncInputImage(const bc::Module& m, const bc::VarRef& ref, const uint8_t* memory, uint8_t* inputImage);

}  // namespace virtcom::plc
