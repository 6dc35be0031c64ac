#include "plc/runtime.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

namespace virtcom::plc {

const char* stateName(PlcState s) {
  switch (s) {
    case PlcState::Stop: return "STOP";
    case PlcState::Run: return "RUN";
    case PlcState::Fault: return "FAULT";
  }
  return "?";
}

Runtime::Runtime(const bc::Module& module, Clock& clock, RuntimeOptions options)
    : module_(module),
      clock_(clock),
      options_(options),
      machine_(module),
      inputs_(module.inputs.size, 0),
      outputs_(module.outputs.size, 0),
      stats_(module.tasks.size()) {
  int64_t g = 0;
  for (const auto& t : module.tasks) g = std::gcd(g, t.intervalNs);
  baseTickNs_ = g > 0 ? g : 10'000'000;
  taskOrder_.resize(module.tasks.size());
  std::iota(taskOrder_.begin(), taskOrder_.end(), 0);
  std::stable_sort(taskOrder_.begin(), taskOrder_.end(),
                   [&](size_t a, size_t b) { return module.tasks[a].priority < module.tasks[b].priority; });
  machine_.setBudget(options_.instructionBudget);
  // A scan of a program compiled with coverage counts its statements: it never repeats the last.
  if (options_.skipRepeatedScans && module.tasks.size() == 1 && module.coverage.probes.empty())
    shadow_.resize(module.writableEnd ? module.writableEnd : module.staticSize);
}

bool Runtime::coldStart() {
  tickIndex_ = 0;
  faultTask_.clear();
  initialised_ = true;
  quiescent_ = false;
  if (!machine_.coldStart()) {
    state_ = PlcState::Fault;
    return false;
  }
  state_ = PlcState::Run;
  return true;
}

bool Runtime::exit() {
  if (!initialised_ || state_ == PlcState::Fault) return true;
  initialised_ = false;
  if (!machine_.runExit()) {
    state_ = PlcState::Fault;
    faultTask_.clear();  // no task: the fault's location names the FB_exit
    return false;
  }
  state_ = PlcState::Stop;
  return true;
}

bool Runtime::runTask(size_t task, int64_t nowNs) {
  const bc::TaskInfo& info = module_.tasks[task];
  uint8_t* mem = machine_.memory();
  // PII: the inputs as they are at the start of the scan
  if (module_.inputs.size) std::memcpy(mem + module_.inputs.address, inputs_.data(), module_.inputs.size);
  machine_.setTaskTimeNs(nowNs);
  int64_t started = monotonicNowNs();
  for (uint32_t p : info.programs) {
    const bc::ProgramInstance& inst = module_.programs[p];
    if (!machine_.run(inst.pou, inst.address)) {
      state_ = PlcState::Fault;
      faultTask_ = info.name;
      return false;
    }
  }
  int64_t took = monotonicNowNs() - started;
  // PIQ: outputs are published only at the end of the scan
  if (module_.outputs.size) std::memcpy(outputs_.data(), mem + module_.outputs.address, module_.outputs.size);
  TaskStats& s = stats_[task];
  if (s.scans == 0 || took < s.minExecNs) s.minExecNs = took;
  s.maxExecNs = std::max(s.maxExecNs, took);
  s.totalExecNs += took;
  ++s.scans;
  return true;
}

bool Runtime::tick() {
  int64_t now = nextTickNs();
  clock_.advanceTo(now);
  ++tickIndex_;
  if (state_ != PlcState::Run) return false;
  bool tracking = !shadow_.empty();
  if (tracking && quiescent_ && inputImageSettled()) {
    ++stats_[0].scans;
    ++stats_[0].skippedScans;
    return true;
  }
  // The tier switch: one null test (and one relaxed load while a compile is pending) per scan.
  if (tierUp_ && tierUp_->readyAfter(tier_.interpScans)) switchToCompiled(now);
  ++(machine_.usesCompiled() ? tier_.compiledScans : tier_.interpScans);
  uint64_t timeReads = machine_.timeReads();
  if (tracking) std::memcpy(shadow_.data(), machine_.memory(), shadow_.size());
  for (size_t t : taskOrder_) {
    int64_t interval = module_.tasks[t].intervalNs;
    if (interval <= 0 || now % interval != 0) continue;
    if (!runTask(t, now)) return false;
  }
  if (tracking)
    quiescent_ = machine_.timeReads() == timeReads && std::memcmp(shadow_.data(), machine_.memory(), shadow_.size()) == 0;
  return true;
}

void Runtime::switchToCompiled(int64_t nowNs) {
  machine_.useCompiled(tierUp_->code());
  tierUp_.reset();
  tier_.switchedAtNs = nowNs;
}

bool Runtime::inputImageSettled() const {
  const bc::ProcessArea& in = module_.inputs;
  return in.size == 0 || std::memcmp(inputs_.data(), machine_.memory() + in.address, in.size) == 0;
}

std::string Runtime::faultText() const {
  if (state_ != PlcState::Fault) return {};
  std::string where = faultTask_.empty() ? "" : " (task " + faultTask_ + ")";
  return machine_.fault().describe(module_) + where;
}

}  // namespace virtcom::plc
