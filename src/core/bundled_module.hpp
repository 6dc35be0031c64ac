#pragma once
// Shared objects built with virtcom and placed next to its executable, loaded on first use.
// A few commands need heavy libraries: the web HMI cpp-httplib (which brings OpenSSL, brotli
// and zlib), `virtcom ad render` Graphviz. Linked into the executable, loading them cost every
// command about 17 ms of CPU at start-up, more than half of a whole gearbox cycle
// (docs/performance.md, "Start-up"). Each sits instead behind a small module holding the code
// that calls it, and only the commands that use it pay for loading it.
#include <string>

#include "core/text_result.hpp"

namespace virtcom {

// The address of `symbol` (an extern "C" function) in the module file `file`, found in the
// directory of the running executable (/proc/self/exe). The module is loaded on the first call
// and stays loaded until the process ends (its threads may run until then). Failure: a message
// naming the file and the loader's reason (missing file, missing library, missing symbol).
// Thread-safe; allocates.
TextResult<void*> bundledModuleSymbol(const std::string& file, const char* symbol);

}  // namespace virtcom
