#pragma once
// Ahead-of-time backend: generates C for a module in several translation units
// (aot/c_source.hpp), compiles them in parallel with the system C compiler into cached objects,
// links those into a cached shared object and loads it for vm::Machine::useCompiled.
// Load time only: runs compilers, touches files, allocates. Thread-safe: no shared mutable
// state, and every temporary file has a name of its own.
#include <cstddef>
#include <memory>
#include <string>

#include "aot/c_source.hpp"
#include "bytecode/module.hpp"
#include "vm/compiled.hpp"

namespace virtcom::aot {

struct CompileOptions {
  // The compiler command, split at spaces ("ccache gcc" works). Empty: $CC, else "cc".
  std::string compiler;
  // Where shared objects are cached. Empty: $VIRTCOM_AOT_CACHE, else $XDG_CACHE_HOME/virtcom/aot,
  // else $HOME/.cache/virtcom/aot, else a folder under the temporary directory.
  std::string cacheDir;
  // Instructions per C translation unit (c_source.hpp); tests set it low to split small modules.
  uint32_t unitInstructions = kUnitInstructions;
  // Compilers run at once; 0: one per hardware thread, at most kMaxJobs.
  unsigned jobs = 0;
};

inline constexpr unsigned kMaxJobs = 8;

struct CompileResult {
  std::shared_ptr<const vm::CompiledCode> code;  // null on failure
  std::string error;                              // why there is no code (one line)
  bool fromCache = false;       // the linked shared object came from the cache
  size_t units = 0;             // translation units of the module (the entry table's included)
  size_t unitsCompiled = 0;     // of those, compiled now; the others' objects came from the cache
};

// Every cache key is a hash of the generated source and the compiler command (a unit's object)
// or of its parts' keys and the link command (the shared object), so a changed module,
// generator or compiler never reuses a stale file, and an edit of one POU recompiles its unit
// and the entry table only.
CompileResult compileModule(const bc::Module& m, const CompileOptions& options = {});

// Whether cached machine code must come from the compiler the options name now (`--backend aot`:
// a changed $CC compiles again) or may come from any (`--backend auto`: a warm cache serves a
// run on a machine whose compiler is gone).
enum class CachedCompiler { Any, Same };

// The module's machine code when a former compileModule of the same module by this build put
// it in the cache, else null code (error "not in the cache"). Found by the cheap key of
// aot/module_key.hpp: generates no C, runs no compiler, writes no file. What `--backend auto`
// looks for before the first scan, and `--backend aot` before it generates the C.
CompileResult loadCachedModule(const bc::Module& m, const CompileOptions& options = {},
                               CachedCompiler compiler = CachedCompiler::Any);

}  // namespace virtcom::aot
