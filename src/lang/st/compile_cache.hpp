#pragma once
// Nothing compiled twice: a program image compiled once is kept on disk under a key of
// everything the compile reads, and the next compile of the same sources by the same binary
// reads it back instead of lexing, parsing, checking and generating again (docs/performance.md,
// "Start-up"). Only compiles without a single diagnostic are kept, so a hit prints what a
// compile would print: nothing.
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::st {

// Where the command line keeps compiled modules: $VIRTCOM_MODULE_CACHE ("off" for no cache),
// else $XDG_CACHE_HOME/virtcom/modules, else ~/.cache/virtcom/modules; "" for no cache.
std::string defaultModuleCacheDir();

// The key of a compile: the binary's build id (the compiler and the standard library are part
// of it), the options, the files already registered in `sources` (they shift the file ids) and
// each input's path, front end and text. "" when the binary has no build id: no cache then.
std::string moduleCacheKey(const std::vector<SourceInput>& inputs, const SourceManager& sources,
                           const CompileOptions& options);

// The module a former compile kept under `key`, checked as a fresh one is (verifyModule), with
// the standard library and the inputs registered in `sources` as the compile registers them;
// null when there is none or it does not read back (then nothing is registered).
std::unique_ptr<bc::Module> loadCachedModule(const std::string& dir, const std::string& key,
                                             const std::vector<SourceInput>& inputs, SourceManager& sources);

// Keeps `m` under `key`: written beside its place and renamed into it, so a concurrent reader
// sees the whole file or none. Failures are silent: the cache is an optimisation.
void storeCachedModule(const std::string& dir, const std::string& key, const bc::Module& m);

}  // namespace virtcom::st
