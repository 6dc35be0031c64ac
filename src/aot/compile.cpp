#include "aot/compile.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "aot/c_source.hpp"
#include "bytecode/verifier.hpp"

extern char** environ;

namespace virtcom::aot {

namespace fs = std::filesystem;

namespace {

// Flags every compiler command gets. No FMA contraction: REAL and LREAL results must round
// exactly like the interpreter's.
const std::vector<std::string> kFlags = {"-O2", "-shared", "-fPIC", "-ffp-contract=off", "-w", "-x", "c"};

std::vector<std::string> compilerCommand(const CompileOptions& o) {
  std::string text = o.compiler;
  if (text.empty()) {
    const char* cc = std::getenv("CC");
    text = cc && *cc ? cc : "cc";
  }
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string w; in >> w;) words.push_back(w);
  words.insert(words.end(), kFlags.begin(), kFlags.end());
  return words;
}

fs::path cacheDirectory(const CompileOptions& o) {
  if (!o.cacheDir.empty()) return o.cacheDir;
  if (const char* d = std::getenv("VIRTCOM_AOT_CACHE"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "virtcom" / "aot";
  if (const char* d = std::getenv("HOME"); d && *d) return fs::path(d) / ".cache" / "virtcom" / "aot";
  return fs::temp_directory_path() / ("virtcom-aot-" + std::to_string(getuid()));
}

// FNV-1a, 64 bits: stable across builds and platforms, unlike std::hash.
std::string hashHex(std::string_view text) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string firstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.find("error") != std::string::npos) return line;
  return line;
}

// Runs the compiler with its output and errors in `log`. Empty on success, else why not.
std::string runCompiler(std::vector<std::string> argv, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return "cannot run the C compiler '" + argv[0] + "'";
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return "lost the C compiler process";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return "no C compiler '" + argv[0] + "' found";
  return "the C compiler failed: " + firstLine(log);
}

CompileResult load(const bc::Module& m, const fs::path& object) {
  CompileResult r;
  void* handle = dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    r.error = std::string("cannot load ") + object.string() + ": " + (why ? why : "?");
    return r;
  }
  auto library = std::shared_ptr<void>(handle, [](void* h) { dlclose(h); });
  const auto* abi = static_cast<const uint32_t*>(dlsym(handle, kAbiSymbol));
  const auto* count = static_cast<const uint32_t*>(dlsym(handle, kCountSymbol));
  const auto* entries = static_cast<const vm::AotEntry*>(dlsym(handle, kEntriesSymbol));
  if (!abi || !count || !entries || *abi != vm::kAotAbiVersion || *count != m.pous.size()) {
    r.error = object.string() + " does not match this module";
    return r;
  }
  auto code = std::make_shared<vm::CompiledCode>();
  code->entries.assign(entries, entries + *count);
  code->library = std::move(library);
  r.code = std::move(code);
  return r;
}

}  // namespace

CompileResult compileModule(const bc::Module& m, const CompileOptions& options) {
  CompileResult r;
  if (std::string problem = bc::verifyModule(m); !problem.empty()) {
    r.error = "the module does not verify: " + problem;
    return r;
  }
  const std::string source = generateCSource(m);
  std::vector<std::string> command = compilerCommand(options);
  std::string commandText;
  for (const auto& w : command) commandText += w + " ";
  const fs::path dir = cacheDirectory(options);
  const std::string key = hashHex(source + '\0' + commandText);
  const fs::path object = dir / (key + ".so");
  std::error_code ec;
  if (fs::exists(object, ec)) {
    r = load(m, object);
    r.fromCache = r.code != nullptr;
    if (r.code) return r;
  }
  fs::create_directories(dir, ec);
  if (ec) {
    r.error = "cannot create the cache folder " + dir.string() + ": " + ec.message();
    return r;
  }
  // Unique temporary names, renamed into place: concurrent loads of one module never see a
  // half-written object.
  const std::string tmp = key + "." + std::to_string(getpid());
  const fs::path cFile = dir / (key + ".c"), tmpC = dir / (tmp + ".c"), tmpSo = dir / (tmp + ".so"),
                 log = dir / (tmp + ".log");
  if (!(std::ofstream(tmpC, std::ios::binary) << source)) {
    r.error = "cannot write " + tmpC.string();
    return r;
  }
  command.insert(command.end(), {"-o", tmpSo.string(), tmpC.string()});
  r.error = runCompiler(command, log);
  if (r.error.empty()) {
    fs::rename(tmpC, cFile, ec);  // kept next to the object for reading and debugging
    fs::rename(tmpSo, object, ec);
    if (!ec) r = load(m, object);
    else r.error = "cannot store " + object.string() + ": " + ec.message();
  }
  fs::remove(tmpC, ec);
  fs::remove(tmpSo, ec);
  fs::remove(log, ec);
  return r;
}

}  // namespace virtcom::aot
