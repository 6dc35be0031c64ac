#include "lang/st/compile_cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "bytecode/module_file.hpp"
#include "bytecode/verifier.hpp"
#include "core/atomic_file.hpp"
#include "core/build_id.hpp"
#include "core/content_hash.hpp"
#include "lang/st/prelude.hpp"

namespace virtcom::st {

namespace fs = std::filesystem;

namespace {

fs::path cacheFile(const std::string& dir, const std::string& key) { return fs::path(dir) / (key + ".module"); }

// Hashes a piece with its length first, so that ("ab", "c") and ("a", "bc") differ.
uint64_t hashPiece(std::string_view piece, uint64_t h) {
  const uint64_t size = piece.size();
  h = hashText(std::string_view(reinterpret_cast<const char*>(&size), sizeof size), h);
  return hashText(piece, h);
}

// The paths a compile of `inputs` leaves in the module's file table (compileProgram registers
// the standard library, then every input, after what `sources` holds).
std::vector<std::string> filesAfterCompile(const std::vector<SourceInput>& inputs, const SourceManager& sources) {
  std::vector<std::string> files;
  for (uint32_t i = 0; i < sources.fileCount(); ++i) files.push_back(sources.path(i));
  files.emplace_back(kStandardLibraryPath);
  for (const SourceInput& in : inputs) files.push_back(in.path);
  return files;
}

}  // namespace

std::string defaultModuleCacheDir() {
  if (const char* d = std::getenv("VIRTCOM_MODULE_CACHE"); d && *d) return std::string(d) == "off" ? "" : d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return (fs::path(d) / "virtcom" / "modules").string();
  if (const char* d = std::getenv("HOME"); d && *d) return (fs::path(d) / ".cache" / "virtcom" / "modules").string();
  return {};
}

std::string moduleCacheKey(const std::vector<SourceInput>& inputs, const SourceManager& sources,
                           const CompileOptions& options) {
  const std::string& buildId = binaryBuildId();
  if (buildId.empty()) return {};
  uint64_t h = hashPiece(buildId, kHashSeed);
  const char flags[] = {options.library ? 'L' : '-', options.coverage ? 'C' : '-'};
  h = hashPiece(std::string_view(flags, sizeof flags), h);
  for (uint32_t i = 0; i < sources.fileCount(); ++i) h = hashPiece(sources.path(i), h);
  for (const SourceInput& in : inputs) {
    h = hashPiece(in.path, h);
    h = hashPiece(in.frontEnd ? "front end" : "ST", h);
    h = hashPiece(in.text, h);
  }
  return hashHex(std::string_view(reinterpret_cast<const char*>(&h), sizeof h));
}

std::unique_ptr<bc::Module> loadCachedModule(const std::string& dir, const std::string& key,
                                             const std::vector<SourceInput>& inputs, SourceManager& sources) {
  std::ifstream in(cacheFile(dir, key), std::ios::binary);
  if (!in) return nullptr;
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  auto module = std::make_unique<bc::Module>();
  if (!bc::decodeModule(bytes, *module).empty() || !bc::verifyModule(*module).empty()) return nullptr;
  if (module->files != filesAfterCompile(inputs, sources)) return nullptr;
  sources.addFile(std::string(kStandardLibraryPath), std::string(standardLibrarySource()));
  for (const SourceInput& input : inputs) sources.addFile(input.path, input.text);
  return module;
}

void storeCachedModule(const std::string& dir, const std::string& key, const bc::Module& m) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path target = cacheFile(dir, key);
  const fs::path tmp = temporaryName(target.string());
  const std::string bytes = bc::encodeModule(m);
  if (std::ofstream(tmp, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size())))
    fs::rename(tmp, target, ec);
  fs::remove(tmp, ec);
}

}  // namespace virtcom::st
