#include "aot/compile.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "aot/module_key.hpp"
#include "bytecode/verifier.hpp"
#include "core/atomic_file.hpp"
#include "core/content_hash.hpp"

extern char** environ;

namespace virtcom::aot {

namespace fs = std::filesystem;

namespace {

// Flags of every unit's compile. No FMA contraction: REAL and LREAL results must round exactly
// like the interpreter's. Optimisation levels never change results otherwise (no fast-math).
const std::vector<std::string> kCompileFlags = {"-O2", "-c", "-fPIC", "-ffp-contract=off", "-w", "-x", "c"};
const std::vector<std::string> kLinkFlags = {"-shared"};

// The compiler command, split at spaces ("ccache gcc" works), followed by `flags`.
std::vector<std::string> compilerCommand(const CompileOptions& o, const std::vector<std::string>& flags) {
  std::string text = o.compiler;
  if (text.empty()) {
    const char* cc = std::getenv("CC");
    text = cc && *cc ? cc : "cc";
  }
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string w; in >> w;) words.push_back(w);
  words.insert(words.end(), flags.begin(), flags.end());
  return words;
}

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& w : words) text += w + " ";
  return text;
}

fs::path cacheDirectory(const CompileOptions& o) {
  if (!o.cacheDir.empty()) return o.cacheDir;
  if (const char* d = std::getenv("VIRTCOM_AOT_CACHE"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "virtcom" / "aot";
  if (const char* d = std::getenv("HOME"); d && *d) return fs::path(d) / ".cache" / "virtcom" / "aot";
  return fs::temp_directory_path() / ("virtcom-aot-" + std::to_string(getuid()));
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

// Runs `command` (which gets "-o OUTPUT [INPUTS]") to produce `target` under a temporary name,
// then renames it into place. `source`, if not empty, is written first and kept next to the
// target as KEY.c, for reading and debugging. Empty on success, else why not.
std::string produce(std::vector<std::string> command, const fs::path& target, const std::string& source,
                    const std::vector<std::string>& inputs) {
  const fs::path dir = target.parent_path();
  const std::string key = target.stem().string(), tmp = temporaryName(key);
  const fs::path tmpOut = dir / (tmp + target.extension().string()), tmpC = dir / (tmp + ".c"), log = dir / (tmp + ".log");
  command.insert(command.end(), {"-o", tmpOut.string()});
  if (!source.empty()) {
    if (!(std::ofstream(tmpC, std::ios::binary) << source)) return "cannot write " + tmpC.string();
    command.push_back(tmpC.string());
  }
  command.insert(command.end(), inputs.begin(), inputs.end());
  std::string error = runCompiler(command, log);
  std::error_code ec;
  if (error.empty()) {
    if (!source.empty()) fs::rename(tmpC, dir / (key + ".c"), ec);
    fs::rename(tmpOut, target, ec);
    if (ec) error = "cannot store " + target.string() + ": " + ec.message();
  }
  fs::remove(tmpC, ec);
  fs::remove(tmpOut, ec);
  fs::remove(log, ec);
  return error;
}

// One unit's object in the cache and how to make it.
struct UnitJob {
  const CUnit* unit;
  fs::path object;
  bool cached;
  std::string error;
};

// Compiles the units not in the cache, up to `jobs` at once. The first failure, in unit
// order, or empty.
std::string compileUnits(std::vector<UnitJob>& work, const std::vector<std::string>& command, unsigned jobs) {
  std::vector<UnitJob*> todo;
  for (auto& w : work)
    if (!w.cached) todo.push_back(&w);
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t i; (i = next++) < todo.size();) todo[i]->error = produce(command, todo[i]->object, todo[i]->unit->source, {});
  };
  std::vector<std::thread> threads;
  const size_t count = std::min<size_t>(jobs, todo.size());
  for (size_t t = 1; t < count; ++t) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  for (const auto& w : work)
    if (!w.error.empty()) return w.error;
  return {};
}

unsigned jobCount(const CompileOptions& o) {
  if (o.jobs != 0) return o.jobs;
  return std::clamp(std::thread::hardware_concurrency(), 1u, kMaxJobs);
}

// Every dlopen and dlclose of compiled code, one at a time. glibc's loader serialises them
// itself, but with a lock of its own that ThreadSanitizer does not see: `virtcom test --jobs 2
// --backend aot` (each case loads and unloads the program's code) was reported as a race inside
// _dl_close_worker. Loading is rare, so holding a lock of ours costs nothing and states the order.
std::mutex& loaderMutex() {
  static std::mutex m;
  return m;
}

CompileResult load(const bc::Module& m, const fs::path& object) {
  CompileResult r;
  void* handle = nullptr;
  const uint32_t *abi = nullptr, *count = nullptr;
  const vm::AotEntry* entries = nullptr;
  {
    std::lock_guard loading(loaderMutex());
    handle = dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      r.error = std::string("cannot load ") + object.string() + ": " + (why ? why : "?");
      return r;
    }
    abi = static_cast<const uint32_t*>(dlsym(handle, kAbiSymbol));
    count = static_cast<const uint32_t*>(dlsym(handle, kCountSymbol));
    entries = static_cast<const vm::AotEntry*>(dlsym(handle, kEntriesSymbol));
  }
  auto library = std::shared_ptr<void>(handle, [](void* h) {
    std::lock_guard unloading(loaderMutex());
    dlclose(h);
  });
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

// Why the module cannot be translated (the generated C trusts verified bytecode), or empty.
std::string untranslatable(const bc::Module& m) {
  std::string problem = bc::verifyModule(m);
  return problem.empty() ? problem : "the module does not verify: " + problem;
}

// A module's translation units and where their objects and the linked shared object live in
// the cache (the keys hash the generated source: no stale file is ever reused).
struct CachePlan {
  std::vector<CUnit> units;
  std::vector<UnitJob> work;  // points into units
  fs::path dir, library;
};

CachePlan planCache(const bc::Module& m, const CompileOptions& options, const std::vector<std::string>& compile,
                    const std::vector<std::string>& link) {
  CachePlan plan;
  plan.units = generateCUnits(m, options.unitInstructions);
  plan.dir = cacheDirectory(options);
  std::string moduleKey = joined(link);
  std::error_code ec;
  for (const CUnit& unit : plan.units) {
    const std::string key = hashHex(unit.source + '\0' + joined(compile));
    moduleKey += key;
    const fs::path object = plan.dir / (key + ".o");
    plan.work.push_back({&unit, object, fs::exists(object, ec), {}});
  }
  plan.library = plan.dir / (hashHex(moduleKey) + ".so");
  return plan;
}

// The cached shared object `library`, loaded; null code (with the reason) when it is not there.
CompileResult loadFromCache(const bc::Module& m, const fs::path& library) {
  std::error_code ec;
  if (library.empty() || !fs::exists(library, ec)) {
    CompileResult r;
    r.error = "not in the cache";
    return r;
  }
  CompileResult cached = load(m, library);
  cached.fromCache = cached.code != nullptr;
  return cached;
}

// The index from a module's cheap key (aot/module_key.hpp) to the name of its shared object:
// KEY.module holds the file name and, on a second line, the hash of the compiler commands that
// made it. The key leaves the compiler out so that `auto` finds a former run's code without a
// reachable compiler; `aot` promises code from the compiler of now, so it checks the second line.
// Written once the shared object is in place.
fs::path indexFile(const fs::path& dir, const std::string& key) { return dir / (key + ".module"); }

std::string compilerKey(const CompileOptions& options) {
  return hashHex(joined(compilerCommand(options, kCompileFlags)) + '\0' + joined(compilerCommand(options, kLinkFlags)));
}

void rememberLibrary(const bc::Module& m, const CompileOptions& options, const fs::path& library) {
  const std::string key = moduleKey(m, options.unitInstructions);
  if (key.empty()) return;
  const fs::path index = indexFile(library.parent_path(), key), tmp = library.parent_path() / temporaryName(key);
  std::error_code ec;
  if (std::ofstream(tmp) << library.filename().string() << '\n' << compilerKey(options) << '\n') fs::rename(tmp, index, ec);
  fs::remove(tmp, ec);
}

fs::path rememberedLibrary(const bc::Module& m, const CompileOptions& options, CachedCompiler compiler) {
  const std::string key = moduleKey(m, options.unitInstructions);
  if (key.empty()) return {};
  const fs::path dir = cacheDirectory(options);
  std::ifstream index(indexFile(dir, key));
  std::string name, madeBy;
  if (!(index >> name) || name.find('/') != std::string::npos) return {};
  if (compiler == CachedCompiler::Same && (!(index >> madeBy) || madeBy != compilerKey(options))) return {};
  return dir / name;
}

}  // namespace

CompileResult compileModule(const bc::Module& m, const CompileOptions& options) {
  CompileResult r;
  if (r.error = untranslatable(m); !r.error.empty()) return r;
  const std::vector<std::string> compile = compilerCommand(options, kCompileFlags),
                                 link = compilerCommand(options, kLinkFlags);
  CachePlan plan = planCache(m, options, compile, link);
  r.units = plan.units.size();
  if (CompileResult cached = loadFromCache(m, plan.library); cached.code) {
    cached.units = r.units;
    rememberLibrary(m, options, plan.library);
    return cached;
  }
  std::error_code ec;
  fs::create_directories(plan.dir, ec);
  if (ec) {
    r.error = "cannot create the cache folder " + plan.dir.string() + ": " + ec.message();
    return r;
  }
  auto& work = plan.work;
  r.unitsCompiled = static_cast<size_t>(std::count_if(work.begin(), work.end(), [](const UnitJob& w) { return !w.cached; }));
  r.error = compileUnits(work, compile, jobCount(options));
  if (!r.error.empty()) return r;
  std::vector<std::string> objects;
  for (const auto& w : work) objects.push_back(w.object.string());
  r.error = produce(link, plan.library, {}, objects);
  if (!r.error.empty()) return r;
  CompileResult loaded = load(m, plan.library);
  loaded.units = r.units;
  loaded.unitsCompiled = r.unitsCompiled;
  if (loaded.code) rememberLibrary(m, options, plan.library);
  return loaded;
}

CompileResult loadCachedModule(const bc::Module& m, const CompileOptions& options, CachedCompiler compiler) {
  CompileResult r;
  if (r.error = untranslatable(m); !r.error.empty()) return r;
  return loadFromCache(m, rememberedLibrary(m, options, compiler));
}

}  // namespace virtcom::aot
