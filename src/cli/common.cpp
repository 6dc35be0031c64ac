#include "cli/common.hpp"
#include "cli/compile_library.hpp"

#include <algorithm>
#include <csignal>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands.hpp"
#include "core/ascii.hpp"
#include "core/duration_units.hpp"
#include "core/head_tail_log.hpp"
#include "lang/ad/reader.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compile_cache.hpp"
#include "lang/st/compiler.hpp"
#include "plc/variable_text.hpp"

namespace virtcom::cli {

std::optional<std::vector<st::SourceInput>> readSources(const std::vector<std::string>& paths) {
  std::vector<st::SourceInput> inputs;
  for (const auto& path : paths) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::cerr << path << ": error: cannot read the file\n";
      return std::nullopt;
    }
    std::stringstream buf;
    buf << in.rdbuf();
    inputs.push_back(plcopen::sourceInput(path, buf.str()));
  }
  return inputs;
}

st::CompileOptions withModuleCache(st::CompileOptions options) {
  if (options.cacheDir.empty()) options.cacheDir = st::defaultModuleCacheDir();
  return options;
}

namespace {
std::unique_ptr<bc::Module> compileWith(const std::vector<std::string>& paths, SourceManager& sources,
                                        Diagnostics& diags, bool printWarnings, st::CompileOptions options) {
  auto inputs = readSources(paths);
  if (!inputs) return nullptr;
  auto module = st::compileProgram(*inputs, sources, diags, withModuleCache(std::move(options)));
  if (!module || printWarnings) std::cerr << diags.render(sources);
  return module;
}
}  // namespace

std::unique_ptr<bc::Module> compileFiles(const std::vector<std::string>& paths, SourceManager& sources,
                                         Diagnostics& diags, bool printWarnings, st::CompileOptions options) {
  return compileWith(paths, sources, diags, printWarnings, options);
}

std::unique_ptr<bc::Module> compileLibraryFiles(const std::vector<std::string>& paths, SourceManager& sources,
                                                Diagnostics& diags) {
  st::CompileOptions options;
  options.library = true;
  return compileWith(paths, sources, diags, true, options);
}

std::unique_ptr<cell::Cell> loadCellFile(const std::string& path, SourceManager& sources,
                                         st::CompileOptions plcOptions) {
  Diagnostics diags;
  auto cell = cell::loadCell(path, sources, diags, withModuleCache(std::move(plcOptions)));
  std::cerr << diags.render(sources);
  return cell;
}

std::string presetVariable(const bc::Module& m, const std::string& assignment, uint8_t* memory, uint8_t* inputImage) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos) return "expected NAME=VALUE, found '" + assignment + "'";
  std::string name = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  auto ref = bc::resolveVariable(m, name);
  if (!ref) return "unknown variable '" + name + "' (use the qualified name, e.g. MAIN.count or GVL.x)";
  if (ref->readOnly) return "'" + name + "' is a CONSTANT and cannot be set";
  std::string problem = plc::writeVariableText(m, *ref, value, memory, inputImage);
  if (!problem.empty()) return name + ": " + problem;
  return {};
}

std::optional<ad::Program> readDiagramFile(const std::string& path) {
  auto inputs = readSources({path});
  if (!inputs) return std::nullopt;
  SourceManager sources;
  Diagnostics diags;
  uint32_t fileId = sources.addFile(path, inputs->front().text);
  ad::Program program = ad::readProgramFile(fileId, path, sources.text(fileId), diags);
  std::cerr << diags.render(sources);
  if (diags.hasErrors()) return std::nullopt;
  return program;
}

bool writeFile(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
  if (!out.flush()) {
    std::cerr << "error: cannot write " << path << "\n";
    return false;
  }
  return true;
}

std::optional<int64_t> parseDurationNs(const std::string& raw) {
  std::string text = asciiLower(raw);
  if (text.rfind("t#", 0) == 0) text = text.substr(2);
  else if (text.rfind("time#", 0) == 0) text = text.substr(5);
  if (text.empty()) return std::nullopt;
  // a bare number is milliseconds
  bool bare = true;
  for (char c : text)
    if (!isAsciiDigit(c) && c != '.') bare = false;
  if (bare) text += "ms";
  double total = 0;
  size_t i = 0;
  while (i < text.size()) {
    size_t start = i;
    while (i < text.size() && (isAsciiDigit(text[i]) || text[i] == '.' || text[i] == '_')) ++i;
    if (start == i) return std::nullopt;
    std::string number;
    for (size_t k = start; k < i; ++k)
      if (text[k] != '_') number += text[k];
    if (std::count(number.begin(), number.end(), '.') > 1) return std::nullopt;
    double value = std::strtod(number.c_str(), nullptr);
    const DurationUnit* unit = iecDurationUnitAtStart(std::string_view(text).substr(i));
    if (unit == nullptr) return std::nullopt;
    total += value * static_cast<double>(unit->ns);
    i += unit->iec.size();
  }
  int64_t ns = static_cast<int64_t>(total + 0.5);
  if (ns <= 0) return std::nullopt;
  return ns;
}

void addTraceWindowOption(CLI::App& cmd, size_t& window) {
  cmd.add_option("--trace-window", window,
                 "keep every activity and cycle of a run while there are at most N of each (default " +
                     std::to_string(kDefaultTraceWindow) +
                     "); a longer run keeps the first and last N/2 for the Gantt chart and sums of the middle (docs/report.md)")
      ->check(CLI::Range(size_t{2}, size_t{1} << 30));
}

std::atomic<bool> gStopRequested{false};

namespace {
extern "C" void requestStop(int) { gStopRequested = true; }
}  // namespace

void stopOnSignals() {
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
}

}  // namespace virtcom::cli
