#pragma once
// Shared pieces of the `virtcom` subcommands.
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "cell/cell.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/ad/diagram.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::cli {

// The compile options of the command line: `options` with the module cache of
// st::defaultModuleCacheDir (a program compiled once is read back next time).
st::CompileOptions withModuleCache(st::CompileOptions options);

// Reads and compiles the files (through the module cache); prints diagnostics to stderr. Null on
// a read or compile error.
std::unique_ptr<bc::Module> compileFiles(const std::vector<std::string>& paths, SourceManager& sources,
                                         Diagnostics& diags, bool printWarnings = true,
                                         st::CompileOptions options = {});

// The help text of every command's FILES argument.
inline constexpr const char* kSourceFilesHelp =
    "ST (.st), activity diagrams (.ad, .adxml), PLCopen XML (.xml) and TwinCAT 3 (.TcPOU, .TcGVL, .TcDUT, .TcIO) files compiled together as one program";

// Reads the files as compiler inputs, each with its front end (plcopen::sourceInput).
// Prints an error and returns nullopt if a file cannot be read.
std::optional<std::vector<st::SourceInput>> readSources(const std::vector<std::string>& paths);

// Reads and checks an activity-diagram file (.ad text, or AD-XML for .adxml); prints its
// diagnostics to stderr. Nullopt on a read or diagram error. `ad tables|convert|export|render`.
std::optional<ad::Program> readDiagramFile(const std::string& path);

// Loads a cell file (its program through the module cache) and prints its diagnostics to stderr.
// Null on any error.
std::unique_ptr<cell::Cell> loadCellFile(const std::string& path, SourceManager& sources,
                                         st::CompileOptions plcOptions = {});

// Applies one `--set NAME=VALUE` to a PLC image. Located inputs (%I) are also written into
// the external input image (when given) so the next scan's input copy keeps the value.
// Returns the error text, empty on success. CONSTANTs are refused.
std::string presetVariable(const bc::Module& m, const std::string& assignment, uint8_t* memory, uint8_t* inputImage);

// Writes `content` to `path` (binary); prints "error: cannot write PATH" and returns false if
// the file cannot be written.
bool writeFile(const std::string& path, const std::string& content);

// Parses a duration such as "10ms", "1.5s", "250us", "T#1s500ms", "100" (ms). Nullopt if invalid.
std::optional<int64_t> parseDurationNs(const std::string& text);

// Set by SIGINT/SIGTERM once stopOnSignals() installed their handlers: the command running in
// this process (one per process) ends its run, writes its reports and exits.
extern std::atomic<bool> gStopRequested;
void stopOnSignals();

}  // namespace virtcom::cli
