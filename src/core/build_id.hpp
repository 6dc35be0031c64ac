#pragma once
// The GNU build id of the running binary: what keys the caches (AOT objects, compiled modules)
// to the code that wrote them, so a rebuilt virtcom never takes an old entry for its own.
#include <string>

namespace virtcom {

// The build id (hex) of the loaded object holding this function (the executable, when core is
// linked into it statically), read from its PT_NOTE segments in memory: no file is read.
// Empty when the object has none (then the caches key on content alone or stay off).
const std::string& binaryBuildId();

}  // namespace virtcom
