#pragma once
// Ahead-of-time backend: generates C for a module (aot/c_source.hpp), compiles it with the
// system C compiler into a cached shared object and loads it for vm::Machine::useCompiled.
// Load time only: runs a compiler, touches files, allocates.
#include <memory>
#include <string>

#include "bytecode/module.hpp"
#include "vm/compiled.hpp"

namespace virtcom::aot {

struct CompileOptions {
  // The compiler command, split at spaces ("ccache gcc" works). Empty: $CC, else "cc".
  std::string compiler;
  // Where shared objects are cached. Empty: $VIRTCOM_AOT_CACHE, else $XDG_CACHE_HOME/virtcom/aot,
  // else $HOME/.cache/virtcom/aot, else a folder under the temporary directory.
  std::string cacheDir;
};

struct CompileResult {
  std::shared_ptr<const vm::CompiledCode> code;  // null on failure
  std::string error;                              // why there is no code (one line)
  bool fromCache = false;
};

// The cache key is a hash of the generated source and the compiler command, so a changed
// module, generator or compiler never reuses a stale object.
CompileResult compileModule(const bc::Module& m, const CompileOptions& options = {});

}  // namespace virtcom::aot
