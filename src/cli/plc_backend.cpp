#include "cli/plc_backend.hpp"

#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>
#include <vector>

#include "aot/compile.hpp"
#include "cli/commands.hpp"
#include "core/clock.hpp"

namespace virtcom::cli {

namespace fs = std::filesystem;

// What the background compile and the command share. The thread holds it too, so it stays
// valid if the command exits first.
struct PlcBackend::Compile {
  explicit Compile(const bc::Module& m) : module(m) {}
  const bc::Module module;  // a copy: the command's module may go first
  std::thread thread;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;             // guarded by mutex
  bool stopping = false;         // guarded by mutex: the command no longer wants the code
  bool compiling = false;        // guarded by mutex: compileModule has begun (it may run the C compiler)
  aot::CompileResult result;     // guarded by mutex, set with done
  int64_t startedNs = monotonicNowNs();
  int64_t tookNs = 0;            // guarded by mutex, set with done
};

namespace {

// How long the destructor waits for the background compile while terminating its compiler
// processes (aot::compileModule then only removes its temporary files), and how often it looks.
constexpr int64_t kCompileStopBoundNs = 2'000'000'000;
constexpr auto kCompileStopPoll = std::chrono::milliseconds(20);

// A run that ends sooner never starts the compile: the interpreter finishes it before any
// compile could (the gearbox cell's whole run is about 30 ms of CPU, a first compile seconds),
// and each of the many short runs of a test suite would otherwise pay for a compile it never
// uses.
// $VIRTCOM_TIER_DELAY_MS replaces it (tests and measurements).
std::chrono::milliseconds tierUpDelay() {
  const char* text = std::getenv("VIRTCOM_TIER_DELAY_MS");
  return std::chrono::milliseconds(text && *text ? std::strtoll(text, nullptr, 10) : 500);
}

// The processes this one started and theirs (read from /proc): the background compile's C
// compiler and what it runs (cc1, as). No command runs other child processes while it runs a
// PLC. Empty where /proc cannot be read.
std::vector<pid_t> descendantProcesses() {
  std::vector<std::pair<pid_t, pid_t>> parentOf;  // (pid, ppid)
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    std::getline(in, stat);
    // "pid (comm) state ppid ...": comm may hold spaces and parentheses, so read after the last ')'.
    const size_t close = stat.rfind(')');
    if (close == std::string::npos || close + 4 >= stat.size()) continue;
    parentOf.emplace_back(std::atoi(name.c_str()), std::atoi(stat.c_str() + close + 4));
  }
  std::vector<pid_t> found{getpid()};
  for (size_t i = 0; i < found.size(); ++i)
    for (const auto& [pid, ppid] : parentOf)
      if (ppid == found[i]) found.push_back(pid);
  found.erase(found.begin());
  return found;
}

uint64_t switchHookScans() {
  const char* text = std::getenv("VIRTCOM_TIER_SWITCH_AT_SCAN");
  return text && *text ? std::strtoull(text, nullptr, 10) : 0;
}

}  // namespace

void addBackendOption(CLI::App& cmd, std::string& backend) {
  cmd.add_option("--backend", backend,
                 "how the PLC runs its program: auto (default) runs machine code from the first scan when the "
                 "cache holds this program's from a former run, else starts on the bytecode interpreter at once and "
                 "switches between two scans to machine code compiled in the background with the system C "
                 "compiler (stays on the interpreter without one); interp: the interpreter only; aot: machine code "
                 "compiled before the first scan (falls back to interp with a notice). See docs/performance.md")
      ->check(CLI::IsMember({"auto", "interp", "aot"}));
}

PlcBackend::PlcBackend(const std::string& backend, const bc::Module& m) : requested_(backend) {
  if (backend == "aot") {
    // A former compile by the same compiler is taken without generating the C again.
    aot::CompileResult r = aot::loadCachedModule(m, {}, aot::CachedCompiler::Same);
    if (!r.code) r = aot::compileModule(m);
    if (!r.code) std::cerr << "notice: --backend aot unavailable, using the interpreter: " << r.error << "\n";
    compiled_ = std::move(r.code);
    return;
  }
  if (backend != "auto") return;
  const uint64_t switchAtScan = switchHookScans();
  // Machine code a former run left in the cache runs from the first scan: no compile to wait for.
  // (Not when a test places the switch: that needs the interpreter first.)
  if (!switchAtScan) {
    aot::CompileResult cached = aot::loadCachedModule(m);
    if (cached.code) {
      compiled_ = std::move(cached.code);
      return;
    }
  }
  handoff_ = std::make_shared<vm::CompiledHandoff>();
  compile_ = std::make_shared<Compile>(m);
  auto work = [compile = compile_, handoff = handoff_](std::chrono::milliseconds delay) {
    {
      std::unique_lock lock(compile->mutex);
      if (delay.count() > 0 && compile->finished.wait_for(lock, delay, [&] { return compile->stopping; })) {
        compile->result.error = "the run ended before the compile started";
        compile->done = true;
        compile->finished.notify_all();
        return;
      }
      compile->compiling = true;
    }
    aot::CompileResult r = aot::compileModule(compile->module);
    if (r.code) handoff->publish(r.code);
    std::lock_guard lock(compile->mutex);
    compile->result = std::move(r);
    compile->tookNs = monotonicNowNs() - compile->startedNs;
    compile->done = true;
    compile->finished.notify_all();
  };
  if (switchAtScan) {
    handoff_->holdUntilScan(switchAtScan);
    work(std::chrono::milliseconds(0));
    return;
  }
  compile_->thread = std::thread(work, tierUpDelay());
}

PlcBackend::~PlcBackend() {
  if (!compile_ || !compile_->thread.joinable()) return;
  std::unique_lock lock(compile_->mutex);
  compile_->stopping = true;
  compile_->finished.notify_all();
  // Terminated again and again until the compile gives up: the thread may still be writing
  // the C source and spawn the compiler after a first round.
  const int64_t deadlineNs = monotonicNowNs() + kCompileStopBoundNs;
  while (!compile_->done && monotonicNowNs() < deadlineNs) {
    // Only a compile under way has processes to end. A run shorter than the tier-up delay ends
    // here without reading /proc (every process's stat file: about 3 % of a gearbox run's
    // instructions, and as many system calls), the waiting thread ends at the notify above.
    if (compile_->compiling)
      for (pid_t pid : descendantProcesses()) kill(pid, SIGTERM);
    compile_->finished.wait_for(lock, kCompileStopPoll, [&] { return compile_->done; });
  }
  const bool done = compile_->done;
  lock.unlock();
  // Still compiling after the bound (a compiler that ignores SIGTERM): the thread finishes
  // alone, on its own copy of the module; the process does not wait for it.
  if (done) compile_->thread.join();
  else compile_->thread.detach();
}

void PlcBackend::attach(plc::Runtime& runtime) const {
  runtime.machine().useCompiled(compiled_);
  runtime.switchToCompiledWhenReady(handoff_);
}

void PlcBackend::logRun(const plc::TierStats& stats) const {
  if (!std::getenv("VIRTCOM_TIER_LOG")) return;
  std::cerr << "tier: --backend " << requested_ << ": " << stats.interpScans << " scans interpreted, "
            << stats.compiledScans << " on machine code";
  if (stats.switchedAtNs >= 0) std::cerr << ", switched at " << static_cast<double>(stats.switchedAtNs) * 1e-9 << " s";
  if (requested_ == "auto" && compiled_) std::cerr << "; machine code from the cache at load";
  if (compile_) {
    std::lock_guard lock(compile_->mutex);
    if (!compile_->done) std::cerr << "; machine code not ready when the run ended";
    else if (compile_->result.code)
      std::cerr << "; machine code ready after " << static_cast<double>(compile_->tookNs) * 1e-6 << " ms"
                << (compile_->result.fromCache ? " (from the cache)" : " (compiled)");
    else std::cerr << "; no machine code: " << compile_->result.error;
  }
  std::cerr << "\n";
}

}  // namespace virtcom::cli
