#pragma once
// A program image as bytes: what the compile cache (lang/st/compile_cache.hpp) keeps on disk so
// that a program compiled once is never compiled again. The bytes hold every member of `Module`
// and a checksum; reading checks every size against what is left and every enumeration against
// its range, so any bytes (a torn or foreign file) give an error, never a crash or an over-read.
// The reader does not judge the code: the caller runs verifyModule as after a compile.
#include <string>
#include <string_view>

#include "bytecode/module.hpp"

namespace virtcom::bc {

// The module as bytes: a magic word and format version, the members, an FNV-1a checksum.
std::string encodeModule(const Module& m);

// The module read back from encodeModule's bytes into `out`; "" on success, else why not
// (e.g. "checksum mismatch", "truncated in 'types'"). `out` is unspecified on failure.
std::string decodeModule(std::string_view bytes, Module& out);

}  // namespace virtcom::bc
